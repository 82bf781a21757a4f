#pragma once

#include <string>

#include <QLabel>
#include <QTimer>

#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::app {

/// The status bar's message line: one line, always, so that a message never changes the height
/// of the status bar (and with it the 3D view above). A message too long for the line is cut
/// with an ellipsis; the whole of it is the line's tooltip. A message is held only while it is
/// true: it goes at the next change of the document or of the selection (clearStale(), called
/// by the window), or when its timeout (if any) runs out, whichever comes first.
class StatusLine : public QLabel {
  Q_OBJECT

 public:
  explicit StatusLine(QWidget* parent = nullptr);
  /// Shows `text`; `timeoutMs` > 0 also clears it after that long.
  void say(const QString& text, int timeoutMs = 0);
  /// The document or the selection changed: what was said no longer holds.
  void clearStale();
  /// The whole message (text() is what fits on the line).
  const QString& message() const { return message_; }

  /// One line of text tall, whatever the message; as wide as the status bar gives.
  QSize sizeHint() const override;
  QSize minimumSizeHint() const override;

 protected:
  void resizeEvent(QResizeEvent* event) override;

 private:
  void setMessage(const QString& text);
  /// The message on one line (line breaks as spaces), cut to the line's width.
  void showFitting();

  QTimer expiry_;
  QString message_;
};

/// A model message as a user reads it: widgets named by their names only ("'knob' (w7)" ->
/// "'knob'", a bare "w7" -> "'knob'") and bindings by what they bind ("b3" -> "the binding
/// 'knob' - 'push'"). Ids the model no longer holds are left as they are.
std::string readableMessage(const widgets::WidgetModel& model, const std::string& message);

}  // namespace ffdkit::app
