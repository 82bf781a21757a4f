// ffdkit::scenes from an installed package: the installed widget file fig6-8.json reads, writes
// and reads back to the same text; the installed press scene reads with its objects and widgets.
// Usage: consumer <prefix>/share/ffdkit.
#include <filesystem>
#include <sstream>

#include "../consumer_check.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/scenes/widget_file.h"

using namespace ffdkit;

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const std::filesystem::path share = argv[1];
  const widgets::WidgetModel model = scenes::readWidgetFile(share / "widgets/fig6-8.json");
  const std::string text = scenes::widgetFileText(model);
  std::istringstream in(text);
  consumer::check(!model.widgets().empty() && scenes::widgetFileText(scenes::readWidgetFile(in)) == text,
                  "a widget file round-trips");
  const scenes::Scene press = scenes::readScene(share / "scenes/press/scene.json");
  consumer::check(!press.objects().empty() && !press.widgets.widgets().empty(), "the press scene reads");
  return consumer::exitCode();
}
