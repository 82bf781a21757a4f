#include "ffdkit/scenes/generator.h"

namespace ffdkit::scenes {

const GeneratorRegistry& builtinGenerators() {
  static const GeneratorRegistry registry = [] {
    GeneratorRegistry r;
    return r;
  }();
  return registry;
}

}  // namespace ffdkit::scenes
