#include "status_line.h"

#include <algorithm>
#include <charconv>
#include <optional>
#include <regex>

#include <QResizeEvent>

namespace ffdkit::app {

StatusLine::StatusLine(QWidget* parent) : QLabel(parent) {
  setObjectName("statusMessage");
  setWordWrap(true);
  setTextInteractionFlags(Qt::TextSelectableByMouse);
  setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);  // wraps instead of widening the window
  expiry_.setSingleShot(true);
  connect(&expiry_, &QTimer::timeout, this, &QLabel::clear);
}

void StatusLine::say(const QString& text, int timeoutMs) {
  setText(text);
  setToolTip(text);
  fitHeight();
  if (timeoutMs > 0) {
    expiry_.start(timeoutMs);
  } else {
    expiry_.stop();
  }
}

void StatusLine::clearStale() {
  expiry_.stop();
  clear();
  setToolTip({});
  fitHeight();
}

void StatusLine::resizeEvent(QResizeEvent* event) {
  QLabel::resizeEvent(event);
  fitHeight();
}

void StatusLine::fitHeight() {
  // One rule for every text, the empty one measured as one line: the status bar (and so the
  // 3D view above it) changes height only when a message needs more lines. (QLabel's own size
  // hint wraps at a width of its choosing, not the one it has.)
  const QMargins margins = contentsMargins();
  const int width = std::max(1, contentsRect().width());
  const QString measured = text().isEmpty() ? QStringLiteral("X") : text();
  const int height = fontMetrics().boundingRect(QRect(0, 0, width, 1 << 20), Qt::TextWordWrap, measured).height() +
                     margins.top() + margins.bottom();
  if (height != fittedHeight_) {
    fittedHeight_ = height;
    updateGeometry();
  }
}

QSize StatusLine::sizeHint() const { return {QLabel::sizeHint().width(), fittedHeight_}; }
QSize StatusLine::minimumSizeHint() const { return {0, fittedHeight_}; }

std::string readableMessage(const widgets::WidgetModel& model, const std::string& message) {
  auto widgetName = [&](std::uint32_t value) -> std::optional<std::string> {
    const widgets::WidgetId id{value};
    if (!model.contains(id)) return std::nullopt;
    return model.name(id);
  };
  // "'name' (w7)": the name is there already.
  static const std::regex labelled(R"(('[^']*') \(w[0-9]+\))");
  std::string text = std::regex_replace(message, labelled, "$1");
  // A bare id: its name, or for a binding the names it binds.
  static const std::regex bare(R"(\b([wb])([0-9]+)\b)");
  std::string out;
  auto last = text.cbegin();
  for (std::sregex_iterator it(text.cbegin(), text.cend(), bare), end; it != end; ++it) {
    const std::smatch& m = *it;
    out.append(last, m[0].first);
    last = m[0].second;
    std::string replacement = m[0].str();
    std::uint32_t value = 0;
    const std::string digits = m[2].str();
    if (std::from_chars(digits.data(), digits.data() + digits.size(), value).ec != std::errc()) {
      out += replacement;
      continue;
    }
    if (m[1] == "w") {
      if (auto name = widgetName(value)) replacement = "'" + *name + "'";
    } else {
      const auto bindings = model.bindings();
      const widgets::BindingId id{value};
      if (std::find(bindings.begin(), bindings.end(), id) != bindings.end()) {
        const widgets::Binding& b = model.binding(id);
        replacement = "the binding '" + model.name(b.from) + "' - '" + model.name(b.to) + "'";
      }
    }
    out += replacement;
  }
  out.append(last, text.cend());
  return out;
}

}  // namespace ffdkit::app
