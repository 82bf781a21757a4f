#pragma once

// Property fields: a control of the property panel that follows a model value. Each function
// returns the field's sync: it puts the model's present value (get()) into the control with its
// signals blocked (the model is not edited back) and says whether the control's shown value
// changed (PropertyPanel::Stats::fieldsUpdated counts those).

#include <functional>
#include <string>
#include <string_view>

#include <QAbstractButton>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QSignalBlocker>
#include <QSpinBox>

namespace ffdkit::app {

inline QString qs(const std::string& s) { return QString::fromStdString(s); }
inline QString qs(std::string_view s) { return QString::fromStdString(std::string(s)); }

/// A spin box named `name` (for tests) that reports a value when editing ends.
inline QDoubleSpinBox* spin(const QString& name, double value, double lo, double hi, int decimals = 4) {
  auto* box = new QDoubleSpinBox;
  box->setObjectName(name);
  box->setRange(lo, hi);
  box->setDecimals(decimals);
  box->setSingleStep(0.05);
  box->setValue(value);
  box->setKeyboardTracking(false);
  return box;
}

template <class Get>
std::function<bool()> spinField(QDoubleSpinBox* box, Get get) {
  return [box, get] {
    const double before = box->value();
    const QSignalBlocker block(box);
    box->setValue(get());
    return box->value() != before;
  };
}

template <class Get>
std::function<bool()> intSpinField(QSpinBox* box, Get get) {
  return [box, get] {
    const int before = box->value();
    const QSignalBlocker block(box);
    box->setValue(get());
    return box->value() != before;
  };
}

template <class Get>
std::function<bool()> comboField(QComboBox* box, Get index) {
  return [box, index] {
    const int before = box->currentIndex();
    const QSignalBlocker block(box);
    box->setCurrentIndex(index());
    return box->currentIndex() != before;
  };
}

template <class Get>
std::function<bool()> checkField(QAbstractButton* button, Get get) {
  return [button, get] {
    const bool before = button->isChecked();
    const QSignalBlocker block(button);
    button->setChecked(get());
    return button->isChecked() != before;
  };
}

template <class Get>
std::function<bool()> textField(QLabel* label, Get text) {
  return [label, text] {
    const QString now = text();
    if (label->text() == now) return false;
    label->setText(now);
    return true;
  };
}

template <class Get>
std::function<bool()> enabledField(QWidget* widget, Get get) {
  return [widget, get] {
    const bool now = get();
    if (widget->isEnabled() == now) return false;
    widget->setEnabled(now);
    return true;
  };
}

}  // namespace ffdkit::app
