#pragma once

#include <string>

#include <QLabel>
#include <QTimer>

#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::app {

/// The status bar's message line: a word-wrapping label, so a long refusal is read whole
/// instead of cut off, holding a message only while it is true. A message goes at the next
/// change of the document or of the selection (clearStale(), called by the window), or when
/// its timeout (if any) runs out, whichever comes first.
class StatusLine : public QLabel {
  Q_OBJECT

 public:
  explicit StatusLine(QWidget* parent = nullptr);
  /// Shows `text`; `timeoutMs` > 0 also clears it after that long.
  void say(const QString& text, int timeoutMs = 0);
  /// The document or the selection changed: what was said no longer holds.
  void clearStale();

  /// As tall as the text wrapped at the current width: the status bar's layout asks these.
  QSize sizeHint() const override;
  QSize minimumSizeHint() const override;
  bool hasHeightForWidth() const override { return false; }  ///< the hints above already are

 protected:
  void resizeEvent(QResizeEvent* event) override;

 private:
  /// As tall as the wrapped text at the current width (the status bar grows with it).
  void fitHeight();

  QTimer expiry_;
  int fittedHeight_ = 0;
};

/// A model message as a user reads it: widgets named by their names only ("'knob' (w7)" ->
/// "'knob'", a bare "w7" -> "'knob'") and bindings by what they bind ("b3" -> "the binding
/// 'knob' - 'push'"). Ids the model no longer holds are left as they are.
std::string readableMessage(const widgets::WidgetModel& model, const std::string& message);

}  // namespace ffdkit::app
