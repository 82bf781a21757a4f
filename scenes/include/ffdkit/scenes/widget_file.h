#pragma once

#include <filesystem>
#include <iosfwd>
#include <stdexcept>
#include <string>

#include "ffdkit/meshio/read_limits.h"
#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::scenes {

/// The widget file format this build reads and writes (docs/widget-file-format.md): a whole
/// reusable deformation tool (Kuriyama 1996, secs. 6.3.3, 6.4): lattice tree, bases, rest
/// shape, current control points, cells, affine widgets, bindings, outside and re-embed policy.
/// It reads every version from 1. Version 2 added control-point weights (rational lattices,
/// Lamousin & Waggenspack 1994); a tool without weights is still written as version 1, byte for
/// byte as before.
inline constexpr int kWidgetFileVersion = 2;

/// A widget file that cannot be read or written. what() says where:
/// `tool.json:14:9: syntax error ...` for malformed JSON,
/// `tool.json /bindings/2/to: unknown widget 'w7' (known: w0, w1, ...)` for content errors.
class WidgetFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Reads a widget model from JSON text. `sourceName` names the text in error messages.
/// @throws WidgetFileError on malformed JSON, a missing, unknown or future format version,
///         unknown keys or names, bad references, shapes or values, and every error that
///         WidgetModel::fromData reports (inconsistent loops...); nothing is returned half-read.
widgets::WidgetModel readWidgetFile(std::istream& in, const std::string& sourceName = "<stream>");
widgets::WidgetModel readWidgetFile(const std::filesystem::path& path);

/// How a widget file is read: its budget (lattice control points, cells, widgets, bindings are
/// charged before they are built; over it, a WidgetFileError says which lattice or list).
struct WidgetReadOptions {
  meshio::ReadLimits limits{};           ///< the read's limits when `budget` is null
  meshio::ReadBudget* budget = nullptr;  ///< a budget shared with an enclosing read (a scene's)
};
widgets::WidgetModel readWidgetFile(std::istream& in, const std::string& sourceName, const WidgetReadOptions& options);
widgets::WidgetModel readWidgetFile(const std::filesystem::path& path, const WidgetReadOptions& options);

/// The canonical JSON text of a model: fixed key order, 2-space indent, short numeric arrays on
/// one line, shortest round-trip numbers, trailing newline. Reading it and writing again gives
/// the same bytes.
std::string widgetFileText(const widgets::WidgetModel& model);

/// Writes widgetFileText(model).
void writeWidgetFile(std::ostream& out, const widgets::WidgetModel& model);
/// Writes atomically (a temporary file beside `path`, then renamed over it).
/// @throws WidgetFileError if the file cannot be written.
void writeWidgetFile(const std::filesystem::path& path, const widgets::WidgetModel& model);

}  // namespace ffdkit::scenes
