// Fuzz target: generator parameters. The first byte picks a builtin generator, the rest is the
// JSON object of its parameters (as in a scene file's "parameters"); the generator then runs,
// its point bound charged first to a small budget (a scene read's budget, lowered here): a few
// bytes that ask for a big tessellation (a curve network at pitch 255: 780,000 points, over a
// minute under ASan and coverage) are refused at once, as a read past --max-points is.
#include <cstdint>
#include <sstream>
#include <string>

#include "ffdkit/meshio/read_limits.h"
#include "ffdkit/scenes/generator.h"
#include "ffdkit/scenes/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto& registry = ffdkit::scenes::builtinGenerators();
  static const std::vector<std::string> names = registry.names();
  const std::string& name = names[data[0] % names.size()];
  std::istringstream in(std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  try {
    const auto parameters = ffdkit::scenes::readGeneratorParameters(in, "fuzz");
    ffdkit::meshio::ReadLimits limits;
    limits.maxPoints = 5'000;
    limits.maxMemoryBytes = 4u << 20;
    ffdkit::meshio::ReadBudget budget(limits);
    (void)registry.generate(name, parameters, 1.0, budget);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
