#include "ffdkit/scenes/generator.h"
#include "generators/generator_support.h"

namespace ffdkit::scenes {

const GeneratorRegistry& builtinGenerators() {
  static const GeneratorRegistry registry = [] {
    GeneratorRegistry r;
    generators::addQuaternionGenerators(r);
    generators::addG3Generators(r);
    generators::addCardinalGenerators(r);
    generators::addPolyhedronGenerators(r);
    generators::addCurvenetGenerators(r);
    return r;
  }();
  return registry;
}

}  // namespace ffdkit::scenes
