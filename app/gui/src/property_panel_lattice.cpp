// The property panel's rows for a lattice: name, counts, basis per axis, outside policy, the
// picked control point's weight, the transformer of a root lattice (position and size per axis),
// cells, parent, what it deforms; and the edit mode's selected points with their weight.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QSignalBlocker>
#include <QSpinBox>
#include <QVBoxLayout>

#include "ffdkit/interaction/edit_controller.h"
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
  if (const auto& picked = controller_.pickedPoint(); picked && picked->lattice == id)
    addWeightRow(id, {picked->index}, "pointWeight");
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

namespace {

// The weight `text` asks for, or nullopt with the reason in `why`: the one home of what a weight
// field accepts (a number, finite and > 0, as WidgetModel::setWeights requires).
std::optional<double> typedWeight(const QString& typed, QString* why) {
  const QString text = typed.trimmed();
  bool number = false;
  const double value = text.toDouble(&number);
  if (!number) *why = QObject::tr("'%1' is not a number: a weight is a number > 0, e.g. 2 or 0.5").arg(text);
  else if (!std::isfinite(value)) *why = QObject::tr("a weight must be finite");
  else if (!(value > 0.0)) *why = QObject::tr("a weight must be > 0 (%1 is not)").arg(text);
  else return value;
  return std::nullopt;
}

// FNV-1a over the selected indices: the edit mode's layout key changes with the selection
// without holding every index.
std::uint64_t selectionHash(const std::vector<Eigen::Index>& indices) {
  std::uint64_t h = 1469598103934665603ull;
  for (const Eigen::Index i : indices) {
    auto v = static_cast<std::uint64_t>(i);
    for (int byte = 0; byte < 8; ++byte, v >>= 8) h = (h ^ (v & 0xffu)) * 1099511628211ull;
  }
  return h;
}

}  // namespace

std::string PropertyPanel::editLayout() const {
  if (edit_ == nullptr || !edit_->editing()) return {};
  const PointSelection& selection = edit_->points();
  const Eigen::Vector3i n = selection.counts();
  return "edit " + widgets::toString(selection.lattice()) + " " + std::to_string(n[0]) + "x" + std::to_string(n[1]) + "x" +
         std::to_string(n[2]) + " " + std::to_string(selection.count()) + " " +
         std::to_string(selectionHash(selection.indices()));
}

void PropertyPanel::showEditedPoints() {
  const PointSelection& selection = edit_->points();
  const widgets::WidgetId id = selection.lattice();
  const std::vector<Eigen::Index> points = selection.indices();
  const auto pointCount = selection.pointCount();
  auto* edited = addLabel(tr("Editing"), [this, id, count = points.size(), pointCount] {
    return tr("%1: %2 of %3 points selected").arg(qs(scene_.widgets.name(id))).arg(count).arg(pointCount);
  });
  edited->setObjectName("editedPoints");
  if (points.empty()) {
    auto* hint = new QLabel(tr("Select points (click, Shift+click, drag a box) to set their weight here."));
    hint->setWordWrap(true);
    form_->addRow(hint);
    return;
  }
  addWeightRow(id, points, "editWeight");
}

void PropertyPanel::addWeightRow(widgets::WidgetId id, const std::vector<Eigen::Index>& points, const QString& name) {
  // A text field, not a spin box: a weight spans decades (0.01 .. 100), and text that is no weight
  // is refused with a message rather than clamped.
  const bool one = points.size() == 1;
  auto* weight = new QLineEdit;
  weight->setObjectName(name);
  weight->setToolTip((one ? tr("Weight of control point %1").arg(points.front())
                          : tr("Weight of the %1 selected control points (Enter sets all of them)").arg(points.size())) +
                     tr(" (rational FFD): > 0; 1 everywhere is the polynomial lattice; Enter applies"));
  auto* message = new QLabel;
  message->setObjectName(name + "Message");
  message->setWordWrap(true);
  message->setStyleSheet("color: #c0392b");
  message->hide();
  // What the field shows: the points' weight, or blank (their range as the placeholder) when
  // they differ.
  auto modelView = [this, id, points] {
    const Eigen::VectorXd all = scene_.widgets.weights(id);
    double lo = all[points.front()], hi = lo;
    for (const Eigen::Index p : points) lo = std::min(lo, all[p]), hi = std::max(hi, all[p]);
    if (lo == hi) return std::pair(QString::number(lo, 'g', 17), QString());
    return std::pair(QString(), tr("differ: %1 to %2").arg(lo, 0, 'g', 6).arg(hi, 0, 'g', 6));
  };
  auto showModel = [weight, message, modelView] {
    weight->setStyleSheet({});
    message->hide();
    const QSignalBlocker block(weight);
    const auto [text, placeholder] = modelView();
    weight->setText(text);
    weight->setPlaceholderText(placeholder);
  };
  showModel();
  fields_.push_back([weight, modelView, showModel] {
    if (std::pair(weight->text(), weight->placeholderText()) == modelView()) return false;
    showModel();
    return true;
  });
  connect(weight, &QLineEdit::returnPressed, this, [this, id, points, weight, message, showModel] {
    QString why;
    const std::optional<double> value = typedWeight(weight->text(), &why);
    if (!value) {
      // Refused: the text stays for the user to correct; the model is not touched.
      weight->setStyleSheet("border: 1px solid #c0392b");
      message->setText(why);
      message->show();
      return;
    }
    if (guarded([&] { controller_.setWeight(id, points, *value); })) showModel();
  });
  auto* cell = new QWidget;
  auto* column = new QVBoxLayout(cell);
  column->setContentsMargins(0, 0, 0, 0);
  column->addWidget(weight);
  column->addWidget(message);
  form_->addRow(one ? tr("Weight of point %1").arg(points.front()) : tr("Weight of %1 points").arg(points.size()), cell);
}

}  // namespace ffdkit::app
