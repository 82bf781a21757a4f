// Fuzz target: the widget-file reader, against a small budget (WidgetReadOptions::limits), then
// the FFD lattice of every lattice it built.
#include <cstdint>
#include <sstream>
#include <string>

#include "ffdkit/scenes/widget_file.h"

namespace {

ffdkit::scenes::WidgetReadOptions smallRead() {
  ffdkit::scenes::WidgetReadOptions options;
  options.limits.maxPoints = 20'000;
  options.limits.maxMemoryBytes = 16u << 20;
  return options;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const ffdkit::scenes::WidgetReadOptions options = smallRead();
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const ffdkit::widgets::WidgetModel model = ffdkit::scenes::readWidgetFile(in, "fuzz", options);
    for (auto lattice : model.widgets(ffdkit::widgets::WidgetType::Lattice)) (void)model.ffdLattice(lattice);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
