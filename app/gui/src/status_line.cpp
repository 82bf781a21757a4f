#include "status_line.h"

#include <algorithm>
#include <charconv>
#include <optional>
#include <regex>

#include <QResizeEvent>

namespace ffdkit::app {

StatusLine::StatusLine(QWidget* parent) : QLabel(parent) {
  setObjectName("statusMessage");
  setTextFormat(Qt::PlainText);
  setWordWrap(false);
  setTextInteractionFlags(Qt::TextSelectableByMouse);
  // Neither a long message widens the window nor a wrapped one heightens the status bar.
  setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
  expiry_.setSingleShot(true);
  connect(&expiry_, &QTimer::timeout, this, [this] { setMessage({}); });
}

void StatusLine::say(const QString& text, int timeoutMs) {
  setMessage(text);
  if (timeoutMs > 0) {
    expiry_.start(timeoutMs);
  } else {
    expiry_.stop();
  }
}

void StatusLine::clearStale() {
  expiry_.stop();
  setMessage({});
}

void StatusLine::setMessage(const QString& text) {
  message_ = text;
  setToolTip(text);
  showFitting();
}

void StatusLine::resizeEvent(QResizeEvent* event) {
  QLabel::resizeEvent(event);
  showFitting();
}

void StatusLine::showFitting() {
  QString line = message_;
  line.replace(QChar('\n'), QChar(' '));
  const QString fitting = fontMetrics().elidedText(line, Qt::ElideRight, std::max(0, contentsRect().width()));
  if (fitting != text()) setText(fitting);
}

QSize StatusLine::sizeHint() const {
  const QMargins margins = contentsMargins();
  return {fontMetrics().horizontalAdvance(message_) + margins.left() + margins.right(),
          fontMetrics().height() + margins.top() + margins.bottom()};
}
QSize StatusLine::minimumSizeHint() const { return {0, sizeHint().height()}; }

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
