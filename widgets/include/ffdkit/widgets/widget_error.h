#pragma once

#include <stdexcept>
#include <string>

namespace ffdkit::widgets {

/// What went wrong, for callers that react differently (the GUI greys out, the CLI exits).
enum class WidgetErrorCode {
  UnknownWidget,    ///< an id or name that the model does not hold
  InvalidArgument,  ///< a value out of range (zero gain, bad counts, index outside the grid...)
  InvalidBinding,   ///< a pair of widgets that cannot be bound, or a self binding
  InconsistentLoop, ///< a binding that would close an inconsistent loop (Kuriyama 1996, sec. 6.2.2)
  GestureState,     ///< begin without end, update without begin...
};

/// Typed error of the widget model. Every throwing member leaves the model unchanged.
/// `where()` is a JSON-pointer-like location into WidgetModelData ("/cells/3/lattice") when
/// the error comes from WidgetModel::fromData, else empty; what() already includes it.
class WidgetError : public std::runtime_error {
 public:
  /// An error of kind `code`; `where` is a location in WidgetModelData, if any.
  WidgetError(WidgetErrorCode code, const std::string& message, std::string where = {});
  /// What went wrong.
  WidgetErrorCode code() const { return code_; }
  /// Location in WidgetModelData ("/cells/3/lattice"), or empty.
  const std::string& where() const { return where_; }
  /// The message without the location prefix.
  const std::string& message() const { return message_; }

 private:
  WidgetErrorCode code_;
  std::string where_;
  std::string message_;
};

}  // namespace ffdkit::widgets
