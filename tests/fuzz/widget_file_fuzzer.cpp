// Fuzz target: the widget-file reader, then the FFD lattice of every lattice it built.
#include <cstdint>
#include <sstream>
#include <string>

#include "ffdkit/scenes/widget_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const ffdkit::widgets::WidgetModel model = ffdkit::scenes::readWidgetFile(in, "fuzz");
    for (auto lattice : model.widgets(ffdkit::widgets::WidgetType::Lattice)) (void)model.ffdLattice(lattice);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
