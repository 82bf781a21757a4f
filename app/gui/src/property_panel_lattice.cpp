// The property panel's rows for a lattice: name, counts, basis per axis, outside policy, the
// picked control point's weight, the transformer of a root lattice (position and size per axis),
// cells, parent, what it deforms.
#include <cmath>

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QSignalBlocker>
#include <QSpinBox>
#include <QVBoxLayout>

#include "ffdkit/interaction/interaction_controller.h"
#include "lattice_bases.h"
#include "property_fields.h"
#include "property_panel.h"

namespace ffdkit::app {

void PropertyPanel::showLattice(widgets::WidgetId id) {
  const auto& m = scene_.widgets;
  auto* nameLabel = new QLabel(qs(m.name(id)));
  fields_.push_back(textField(nameLabel, [this, id] { return qs(scene_.widgets.name(id)); }));
  form_->addRow(tr("Lattice"), nameLabel);
  // Counts: the model resamples the lattice, keeping its deformation (WidgetModel::setLatticeCounts).
  const Eigen::Vector3i n = m.counts(id);
  auto* countsRow = new QWidget;
  auto* countsLayout = new QHBoxLayout(countsRow);
  countsLayout->setContentsMargins(0, 0, 0, 0);
  for (int axis = 0; axis < 3; ++axis) {
    auto* count = new QSpinBox;
    count->setObjectName(QString("count%1").arg("UVW"[axis]));
    count->setRange(2, 64);
    count->setValue(n[axis]);
    count->setKeyboardTracking(false);
    fields_.push_back(intSpinField(count, [this, id, axis] { return scene_.widgets.counts(id)[axis]; }));
    count->setToolTip(tr("points along %1").arg("uvw"[axis]));
    connect(count, &QSpinBox::valueChanged, this, [this, id, axis, count](int value) {
      const bool done = guarded([&] {
        Eigen::Vector3i c = scene_.widgets.counts(id);
        c[axis] = value;
        controller_.setLatticeCounts(id, c);
      });
      if (!done) {
        const QSignalBlocker block(count);
        count->setValue(scene_.widgets.counts(id)[axis]);
      }
    });
    countsLayout->addWidget(count);
  }
  form_->addRow(tr("Counts (u v w)"), countsRow);
  const auto& settings = m.latticeSettings(id);
  form_->addRow(tr("Shape"), new QLabel(settings.cylinder ? tr("cylindrical (EFFD)") : tr("box")));
  for (int axis = 0; axis < 3; ++axis) {
    const auto a = static_cast<std::size_t>(axis);
    const bool angular = settings.basis[a].kind == ffd::AxisBasis::Kind::PeriodicBSpline;
    const std::vector<ffd::AxisBasis> choices = basisChoices(settings.basis[a], angular);
    auto* basis = new QComboBox;
    basis->setObjectName(QString("basis%1").arg("UVW"[axis]));
    for (const ffd::AxisBasis& b : choices) basis->addItem(basisName(b));
    basis->setCurrentIndex(basisIndex(choices, settings.basis[a]));
    fields_.push_back(
        comboField(basis, [this, id, a, choices] { return basisIndex(choices, scene_.widgets.latticeSettings(id).basis[a]); }));
    connect(basis, &QComboBox::currentIndexChanged, this, [this, id, a, choices, basis](int index) {
      if (index < 0) return;
      const bool done = guarded([&] {
        widgets::LatticeSettings s = scene_.widgets.latticeSettings(id);
        s.basis[a] = choices[static_cast<std::size_t>(index)];
        controller_.setLatticeSettings(id, s);
      });
      if (!done) {
        const QSignalBlocker block(basis);
        basis->setCurrentIndex(basisIndex(choices, scene_.widgets.latticeSettings(id).basis[a]));
      }
    });
    form_->addRow(tr("Basis %1").arg("uvw"[axis]), basis);
  }
  auto* outside = new QComboBox;
  outside->setObjectName("outside");
  outside->addItems({tr("identity"), tr("clamp edge"), tr("extrapolate"), tr("falloff")});
  outside->setCurrentIndex(static_cast<int>(settings.outside.kind));
  fields_.push_back(
      comboField(outside, [this, id] { return static_cast<int>(scene_.widgets.latticeSettings(id).outside.kind); }));
  connect(outside, &QComboBox::currentIndexChanged, this, [this, id](int index) {
    guarded([&] {
      widgets::LatticeSettings s = scene_.widgets.latticeSettings(id);
      s.outside.kind = static_cast<ffd::OutsidePolicy::Kind>(index);
      if (s.outside.kind == ffd::OutsidePolicy::Kind::Falloff && !(s.outside.distance > 0.0)) s.outside.distance = 0.25;
      controller_.setLatticeSettings(id, s);
    });
  });
  form_->addRow(tr("Outside points"), outside);
  if (const auto& picked = controller_.pickedPoint(); picked && picked->lattice == id) addWeightRow(id, picked->index);
  const auto parent = m.parentCell(id);
  if (!parent) {
    // The transformer of a root lattice: position (its lower corner) and size per axis; the
    // orientation is kept.
    const Eigen::Affine3d frame = m.latticeFrame(id);
    const Eigen::Matrix3d linear = frame.linear();
    auto* placement = new QWidget;
    auto* row = new QHBoxLayout(placement);
    row->setContentsMargins(0, 0, 0, 0);
    auto* sizes = new QWidget;
    auto* sizeRow = new QHBoxLayout(sizes);
    sizeRow->setContentsMargins(0, 0, 0, 0);
    for (int axis = 0; axis < 3; ++axis) {
      auto* position = spin(QString("latticePosition%1").arg("xyz"[axis]), frame.translation()[axis], -1e4, 1e4, 3);
      fields_.push_back(spinField(position, [this, id, axis] { return scene_.widgets.latticeFrame(id).translation()[axis]; }));
      connect(position, &QDoubleSpinBox::valueChanged, this, [this, id, axis](double v) {
        guarded([&] {
          Eigen::Affine3d f = scene_.widgets.latticeFrame(id);
          f.translation()[axis] = v;
          controller_.setLatticeFrame(id, f);
        });
      });
      row->addWidget(position);
      auto* size = spin(QString("latticeSize%1").arg("uvw"[axis]), linear.col(axis).norm(), 1e-4, 1e4, 3);
      fields_.push_back(spinField(size, [this, id, axis] { return scene_.widgets.latticeFrame(id).linear().col(axis).norm(); }));
      connect(size, &QDoubleSpinBox::valueChanged, this, [this, id, axis](double v) {
        guarded([&] {
          Eigen::Affine3d f = scene_.widgets.latticeFrame(id);
          f.linear().col(axis) = f.linear().col(axis).normalized() * v;
          controller_.setLatticeFrame(id, f);
        });
      });
      sizeRow->addWidget(size);
    }
    form_->addRow(tr("Position"), placement);
    form_->addRow(tr("Size"), sizes);
  }
  addLabel(tr("Cells"), [this, id] { return QString::number(scene_.widgets.cellsOf(id).size()); });
  addLabel(tr("Parent"), [this, id] {
    const auto cell = scene_.widgets.parentCell(id);
    return cell ? qs(scene_.widgets.name(*cell)) : tr("(root)");
  });
  // A child lattice deforms what its root is attached to (the pipeline runs the whole tree).
  addLabel(tr("Deforms"), [this, id] {
    const auto& model = scene_.widgets;
    widgets::WidgetId root = id;
    while (const auto up = model.parentLattice(root)) root = *up;
    QStringList objects;
    for (const auto& a : scene_.attachments())
      if (a.lattice == root)
        for (const auto o : a.objects) objects << qs(scene_.objectName(o));
    QString deforms = objects.isEmpty() ? tr("(nothing)") : objects.join(", ");
    if (root != id && !objects.isEmpty()) deforms += tr(" (through %1)").arg(qs(model.name(root)));
    return deforms;
  })->setObjectName("deforms");
}

void PropertyPanel::addWeightRow(widgets::WidgetId id, Eigen::Index point) {
  // A text field, not a spin box: a weight spans decades (0.01 .. 100), and text that is no weight
  // is refused with a message rather than clamped.
  auto* weight = new QLineEdit;
  weight->setObjectName("pointWeight");
  weight->setToolTip(tr("Weight of control point %1 (rational FFD): > 0; 1 everywhere is the polynomial lattice; "
                        "Enter applies")
                         .arg(point));
  auto* message = new QLabel;
  message->setObjectName("pointWeightMessage");
  message->setWordWrap(true);
  message->setStyleSheet("color: #c0392b");
  message->hide();
  auto modelText = [this, id, point] { return QString::number(scene_.widgets.weights(id)[point], 'g', 17); };
  weight->setText(modelText());
  auto showModel = [weight, message, modelText] {
    weight->setStyleSheet({});
    message->hide();
    const QSignalBlocker block(weight);
    weight->setText(modelText());
  };
  fields_.push_back([weight, modelText, showModel] {
    if (weight->text() == modelText()) return false;
    showModel();
    return true;
  });
  connect(weight, &QLineEdit::returnPressed, this, [this, id, point, weight, message, showModel] {
    const QString text = weight->text().trimmed();
    bool number = false;
    const double value = text.toDouble(&number);
    QString why;
    if (!number) why = tr("'%1' is not a number: a weight is a number > 0, e.g. 2 or 0.5").arg(text);
    else if (!std::isfinite(value)) why = tr("a weight must be finite");
    else if (!(value > 0.0)) why = tr("a weight must be > 0 (%1 is not)").arg(text);
    if (!why.isEmpty()) {
      // Refused: the text stays for the user to correct; the model is not touched.
      weight->setStyleSheet("border: 1px solid #c0392b");
      message->setText(why);
      message->show();
      return;
    }
    if (guarded([&] { controller_.setWeight(id, point, value); })) showModel();
  });
  auto* cell = new QWidget;
  auto* column = new QVBoxLayout(cell);
  column->setContentsMargins(0, 0, 0, 0);
  column->addWidget(weight);
  column->addWidget(message);
  form_->addRow(tr("Weight of point %1").arg(point), cell);
}

}  // namespace ffdkit::app
