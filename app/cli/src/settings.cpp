// --set NAME=VALUE: parsed and applied to a scene's affine widgets (commands.h). Apart from
// cli.cpp, so that the modules (modules.h) take it without the list of commands.
#include <stdexcept>
#include <string>

#include "commands.h"

namespace ffdkit::cli {

std::vector<VariationSetting> parseSettings(const std::vector<std::string>& texts) {
  std::vector<VariationSetting> settings;
  for (const auto& text : texts) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0) throw UsageError("--set takes NAME=VALUE, got '" + text + "'");
    settings.push_back({text.substr(0, eq), parseNumber(text.substr(eq + 1), "--set " + text.substr(0, eq))});
  }
  return settings;
}

void applySettings(widgets::WidgetModel& model, const std::vector<VariationSetting>& settings) {
  for (const auto& setting : settings) {
    widgets::WidgetId id;
    try {
      id = model.find(setting.widget);
    } catch (const std::exception&) {
      std::string known;
      for (auto affine : model.widgets(widgets::WidgetType::Affine)) known += (known.empty() ? "" : ", ") + model.name(affine);
      throw std::runtime_error("--set: unknown widget '" + setting.widget + "' (affine widgets: " +
                               (known.empty() ? "none" : known) + ")");
    }
    if (model.type(id) != widgets::WidgetType::Affine)
      throw std::runtime_error("--set: '" + setting.widget + "' is a " +
                               std::string(widgets::widgetTypeName(model.type(id))) +
                               " widget; only affine widgets have a variation");
    model.setVariation(id, setting.value);
  }
}

}  // namespace ffdkit::cli
