#pragma once
// Private to scenes: the widget-file JSON of a model, shared by widget files and by scene
// files that hold their widgets inline.

#include <string>

#include "ffdkit/meshio/read_limits.h"
#include "ffdkit/widgets/widget_model.h"
#include "json_text.h"

namespace ffdkit::scenes::detail {

/// Builds a model from a widget-file JSON document; errors (WidgetFileError) name
/// `sourceName` and the JSON pointer below `pointer` (e.g. "/widgets" inside a scene). Its
/// lattices, cells, widgets and bindings are charged to `budget` before they are built.
widgets::WidgetModel widgetModelFromJson(const Json& root, const std::string& sourceName, const std::string& pointer,
                                         meshio::ReadBudget& budget);

/// The widget-file JSON document of a model (canonical key order).
Json widgetModelToJson(const widgets::WidgetModel& model);

}  // namespace ffdkit::scenes::detail
