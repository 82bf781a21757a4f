#include "property_panel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QSignalBlocker>
#include <QSpinBox>
#include <QToolButton>
#include <QVBoxLayout>

#include "ffdkit/interaction/edit_controller.h"
#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/parts/parts.h"
#include "lattice_bases.h"
#include "property_fields.h"

namespace ffdkit::app {

PropertyPanel::PropertyPanel(InteractionController& controller, const scenes::Scene& scene, const EditController* edit,
                             QWidget* parent)
    : QWidget(parent), controller_(controller), scene_(scene), edit_(edit) {
  setObjectName("propertyPanel");
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addStretch();
  clearRows();
}

void PropertyPanel::clearRows() {
  if (content_ != nullptr) {
    layout()->removeWidget(content_);
    content_->hide();
    content_->deleteLater();
  }
  fields_.clear();
  content_ = new QWidget;
  form_ = new QFormLayout(content_);
  static_cast<QVBoxLayout*>(layout())->insertWidget(0, content_);
}

std::string PropertyPanel::layoutOf(const std::vector<OutlinerEntry>& selection) const {
  if (selection.empty()) return "none";
  std::string key = std::to_string(selection.size()) + ":";
  const OutlinerEntry& e = selection.front();
  const auto& m = scene_.widgets;
  switch (e.kind) {
    case OutlinerEntry::Kind::Object: {
      const scenes::SceneObject* object = scene_.findObject(e.object);
      if (object == nullptr) return key + "gone";
      return key + "object " + object->name + (object->mesh.triangles.rows() > 0 ? " surface" : "") +
             (object->mesh.segments.rows() > 0 ? " curve" : "");
    }
    case OutlinerEntry::Kind::Binding: {
      const auto all = m.bindings();
      if (!e.binding.valid() || std::find(all.begin(), all.end(), e.binding) == all.end()) return key + "gone";
      return key + widgets::toString(e.binding) + " " + std::string(bindingKindName(m.binding(e.binding).kind));
    }
    case OutlinerEntry::Kind::Widget: break;
  }
  if (!m.contains(e.widget)) return key + "gone";
  key += widgets::toString(e.widget) + " " + std::string(widgetTypeName(m.type(e.widget)));
  switch (m.type(e.widget)) {
    case widgets::WidgetType::Affine: return key + " " + std::string(affineKindName(m.affineKind(e.widget)));
    case widgets::WidgetType::Cell: return key;
    case widgets::WidgetType::Lattice: break;
  }
  const auto& settings = m.latticeSettings(e.widget);
  // The picked control point's weight row names its point.
  if (const auto& point = controller_.pickedPoint(); point && point->lattice == e.widget)
    key += " point " + std::to_string(point->index);
  key += m.parentCell(e.widget) ? " child" : " root";
  key += settings.cylinder ? " cylinder" : " box";
  for (const ffd::AxisBasis& axis : settings.basis)
    for (const ffd::AxisBasis& b : basisChoices(axis, axis.kind == ffd::AxisBasis::Kind::PeriodicBSpline))
      key.append(1, ' ').append(basisName(b).toStdString());
  return key;
}

void PropertyPanel::showSelection(const std::vector<OutlinerEntry>& selection) {
  const scenes::SceneChanges changes = scenes::changesSince(scene_, mark_);
  mark_ = scenes::markOf(scene_);
  const std::string shape = editLayout() + "|" + layoutOf(selection);
  const bool sameRows = !layout_.empty() && shape == layout_ && selection.size() == shown_.size() &&
                        std::equal(selection.begin(), selection.end(), shown_.begin(), [](const auto& a, const auto& b) {
                          return a.kind == b.kind && a.object == b.object && a.widget == b.widget && a.binding == b.binding;
                        });
  if (sameRows) {
    if (changes.empty()) return;  // a hover, the same selection again
    for (const auto& field : fields_)
      if (field()) ++stats_.fieldsUpdated;
    return;
  }
  shown_ = selection;
  layout_ = shape;
  ++stats_.rebuilds;
  clearRows();
  const bool editing = edit_ != nullptr && edit_->editing();
  if (editing) showEditedPoints();
  if (selection.empty()) {
    if (editing) return;
    auto* hint = new QLabel(tr("Nothing selected. Click a glyph, a lattice point or a row of the outliner."));
    hint->setWordWrap(true);
    form_->addRow(hint);
    return;
  }
  if (selection.size() > 1) form_->addRow(tr("Selected"), new QLabel(tr("%1 items").arg(selection.size())));
  const OutlinerEntry& e = selection.front();
  const auto& m = scene_.widgets;
  switch (e.kind) {
    case OutlinerEntry::Kind::Object:
      if (const scenes::SceneObject* object = scene_.findObject(e.object)) showObject(object->name);
      break;
    case OutlinerEntry::Kind::Binding:
      if (e.binding.valid()) showBinding(e.binding);
      break;
    case OutlinerEntry::Kind::Widget:
      if (!m.contains(e.widget)) break;
      switch (m.type(e.widget)) {
        case widgets::WidgetType::Affine: showAffine(e.widget); break;
        case widgets::WidgetType::Lattice: showLattice(e.widget); break;
        case widgets::WidgetType::Cell: showCell(e.widget); break;
      }
      break;
  }
}

void PropertyPanel::showAffine(widgets::WidgetId id) {
  const auto& m = scene_.widgets;
  auto* nameLabel = new QLabel(qs(m.name(id)));
  fields_.push_back(textField(nameLabel, [this, id] { return qs(scene_.widgets.name(id)); }));
  form_->addRow(tr("Name"), nameLabel);
  const widgets::AffineKind kind = m.affineKind(id);
  // Kind: the points stay, the variation restarts at 0 (WidgetModel::setAffineKind).
  auto* kindBox = new QComboBox;
  kindBox->setObjectName("kind");
  for (auto k : {widgets::AffineKind::Translate, widgets::AffineKind::Rotate, widgets::AffineKind::Scale})
    kindBox->addItem(qs(affineKindName(k)), static_cast<int>(k));
  kindBox->setCurrentIndex(kindBox->findData(static_cast<int>(kind)));
  connect(kindBox, &QComboBox::currentIndexChanged, this, [this, id, kindBox](int index) {
    const auto chosen = static_cast<widgets::AffineKind>(kindBox->itemData(index).toInt());
    if (!guarded([&] { controller_.setAffineKind(id, chosen); })) {
      const QSignalBlocker block(kindBox);
      kindBox->setCurrentIndex(kindBox->findData(static_cast<int>(scene_.widgets.affineKind(id))));
    }
  });
  form_->addRow(tr("Kind"), kindBox);
  const auto cell = m.attachedCell(id);
  auto* cellLabel = new QLabel(cell ? qs(m.name(*cell)) : tr("(free)"));
  fields_.push_back(textField(cellLabel, [this, id] {
    const auto c = scene_.widgets.attachedCell(id);
    return c ? qs(scene_.widgets.name(*c)) : tr("(free)");
  }));
  form_->addRow(tr("Cell"), cellLabel);
  const QString unit = kind == widgets::AffineKind::Translate ? tr("distance")
                       : kind == widgets::AffineKind::Rotate  ? tr("radians")
                                                              : tr("log scale");
  auto* variation = spin("variation", m.variation(id), -1e6, 1e6);
  fields_.push_back(spinField(variation, [this, id] { return scene_.widgets.variation(id); }));
  connect(variation, &QDoubleSpinBox::valueChanged, this,
          [this, id](double v) { guarded([&] { controller_.setVariation(id, v); }); });
  form_->addRow(tr("Variation (%1)").arg(unit), variation);

  // Placement: position in the cell's rest frame (orientation kept).
  const Eigen::Affine3d placement = m.placement(id);
  auto* position = new QWidget;
  auto* row = new QHBoxLayout(position);
  row->setContentsMargins(0, 0, 0, 0);
  for (int axis = 0; axis < 3; ++axis) {
    auto* box = spin(QString("placement%1").arg("xyz"[axis]), placement.translation()[axis], -1e3, 1e3, 3);
    fields_.push_back(spinField(box, [this, id, axis] { return scene_.widgets.placement(id).translation()[axis]; }));
    connect(box, &QDoubleSpinBox::valueChanged, this, [this, id, axis](double v) {
      guarded([&] {
        Eigen::Affine3d p = scene_.widgets.placement(id);
        p.translation()[axis] = v;
        controller_.setPlacement(id, p);
      });
    });
    row->addWidget(box);
  }
  form_->addRow(tr("Position"), position);

  // Orientation: Euler angles (degrees) about z, y', x'' of the placement (position kept).
  const Eigen::Matrix3d rotation = placement.rotation();
  const Eigen::Vector3d euler = rotation.eulerAngles(2, 1, 0) * (180.0 / std::numbers::pi);
  auto* orientation = new QWidget;
  auto* angles = new QHBoxLayout(orientation);
  angles->setContentsMargins(0, 0, 0, 0);
  std::array<QDoubleSpinBox*, 3> boxes{};
  for (int i = 0; i < 3; ++i) {
    boxes[static_cast<std::size_t>(i)] = spin(QString("orientation%1").arg("zyx"[i]), euler[i], -360.0, 360.0, 2);
    fields_.push_back(spinField(boxes[static_cast<std::size_t>(i)], [this, id, i] {
      const Eigen::Matrix3d r = scene_.widgets.placement(id).rotation();
      return r.eulerAngles(2, 1, 0)[i] * (180.0 / std::numbers::pi);
    }));
    angles->addWidget(boxes[static_cast<std::size_t>(i)]);
  }
  for (auto* box : boxes)
    connect(box, &QDoubleSpinBox::valueChanged, this, [this, id, boxes](double) {
      guarded([&] {
        const double k = std::numbers::pi / 180.0;
        Eigen::Affine3d p = scene_.widgets.placement(id);
        const Eigen::Vector3d scale(p.linear().col(0).norm(), p.linear().col(1).norm(), p.linear().col(2).norm());
        const Eigen::Matrix3d r = (Eigen::AngleAxisd(boxes[0]->value() * k, Eigen::Vector3d::UnitZ()) *
                                   Eigen::AngleAxisd(boxes[1]->value() * k, Eigen::Vector3d::UnitY()) *
                                   Eigen::AngleAxisd(boxes[2]->value() * k, Eigen::Vector3d::UnitX()))
                                      .toRotationMatrix();
        p.linear() = r * scale.asDiagonal();
        controller_.setPlacement(id, p);
      });
    });
  form_->addRow(tr("Orientation (z y x, deg)"), orientation);

  // Glyph: the default shape of the kind or a part of the library, and its size.
  const widgets::Glyph glyph = m.glyph(id);
  auto* shape = new QComboBox;
  shape->setObjectName("glyph");
  shape->addItem(tr("default"), QString());
  for (const auto& part : partNames()) shape->addItem(qs(part), qs(part));
  const int current = shape->findData(partMesh(glyph.shape) ? qs(glyph.shape) : QString());
  shape->setCurrentIndex(std::max(0, current));
  fields_.push_back(comboField(shape, [this, id, shape] {
    const std::string& now = scene_.widgets.glyph(id).shape;
    return std::max(0, shape->findData(partMesh(now) ? qs(now) : QString()));
  }));
  connect(shape, &QComboBox::currentIndexChanged, this, [this, id, shape](int) {
    guarded([&] {
      widgets::Glyph g = scene_.widgets.glyph(id);
      const QString part = shape->currentData().toString();
      if (part.isEmpty()) {
        g.shape = std::string(scene_.widgets.affineKind(id) == widgets::AffineKind::Translate ? "arrow"
                              : scene_.widgets.affineKind(id) == widgets::AffineKind::Rotate  ? "ring"
                                                                                               : "cube");
      } else {
        g.shape = part.toStdString();
      }
      controller_.setGlyph(id, g);
    });
  });
  form_->addRow(tr("Glyph / part"), shape);
  auto* size = spin("glyphSize", glyph.size, 0.001, 100.0, 3);
  fields_.push_back(spinField(size, [this, id] { return scene_.widgets.glyph(id).size; }));
  connect(size, &QDoubleSpinBox::valueChanged, this, [this, id](double v) {
    guarded([&] {
      widgets::Glyph g = scene_.widgets.glyph(id);
      g.size = v;
      controller_.setGlyph(id, g);
    });
  });
  form_->addRow(tr("Glyph size"), size);
}

void PropertyPanel::showBinding(widgets::BindingId id) {
  const auto& m = scene_.widgets;
  const widgets::Binding& b = m.binding(id);
  form_->addRow(tr("Binding"), new QLabel(qs(bindingKindName(b.kind))));
  auto* from = new QLabel(qs(m.name(b.from)));
  auto* to = new QLabel(qs(m.name(b.to)));
  fields_.push_back(textField(from, [this, id] { return qs(scene_.widgets.name(scene_.widgets.binding(id).from)); }));
  fields_.push_back(textField(to, [this, id] { return qs(scene_.widgets.name(scene_.widgets.binding(id).to)); }));
  form_->addRow(tr("From"), from);
  form_->addRow(tr("To"), to);
  // Direction: one way = only `from` drives `to` (for an attachment or a hierarchy: the cell
  // drives its widget or child lattice, which no longer move the cell).
  auto* oneWay = new QCheckBox(tr("one way (only '%1' drives)").arg(qs(m.name(b.from))));
  oneWay->setObjectName("oneWay");
  oneWay->setChecked(b.oneWay);
  fields_.push_back(checkField(oneWay, [this, id] { return scene_.widgets.binding(id).oneWay; }));
  fields_.push_back([this, id, oneWay] {
    const QString now = tr("one way (only '%1' drives)").arg(qs(scene_.widgets.name(scene_.widgets.binding(id).from)));
    if (oneWay->text() == now) return false;
    oneWay->setText(now);
    return true;
  });
  connect(oneWay, &QCheckBox::toggled, this, [this, id, oneWay](bool checked) {
    if (!guarded([&] { controller_.setOneWay(id, checked); })) {
      const QSignalBlocker block(oneWay);
      oneWay->setChecked(scene_.widgets.binding(id).oneWay);
    }
  });
  form_->addRow(tr("Direction"), oneWay);
  if (b.kind != widgets::BindingKind::Variation) {
    auto* masks = new QWidget;
    auto* row = new QHBoxLayout(masks);
    row->setContentsMargins(0, 0, 0, 0);
    const bool on[3] = {b.mask.translate, b.mask.rotate, b.mask.scale};
    for (int c = 0; c < 3; ++c) {
      auto* button = new QToolButton;
      const QString letter = QString("TRS"[c]);
      button->setObjectName("mask" + letter);
      button->setText(letter);
      button->setCheckable(true);
      button->setChecked(on[c]);
      fields_.push_back(checkField(button, [this, id, c] {
        const widgets::AffineMask mask = scene_.widgets.binding(id).mask;
        return c == 0 ? mask.translate : c == 1 ? mask.rotate : mask.scale;
      }));
      button->setToolTip(QStringList{tr("translation"), tr("rotation"), tr("scale")}[c]);
      connect(button, &QToolButton::toggled, this, [this, id, c](bool checked) {
        guarded([&] {
          widgets::AffineMask mask = scene_.widgets.binding(id).mask;
          (c == 0 ? mask.translate : c == 1 ? mask.rotate : mask.scale) = checked;
          controller_.setMask(id, mask);
        });
      });
      row->addWidget(button);
    }
    row->addStretch();
    form_->addRow(tr("Mask"), masks);
    return;
  }
  auto* gain = spin("gain", b.rule.gain, -1e4, 1e4);
  fields_.push_back(spinField(gain, [this, id] { return scene_.widgets.binding(id).rule.gain; }));
  connect(gain, &QDoubleSpinBox::valueChanged, this, [this, id](double v) {
    guarded([&] {
      widgets::ConversionRule rule = scene_.widgets.binding(id).rule;
      rule.gain = v;
      controller_.setRule(id, rule);
    });
  });
  form_->addRow(tr("Gain (to per from)"), gain);
  auto* clamp = new QCheckBox(tr("clamp the 'to' variation"));
  clamp->setObjectName("clamp");
  clamp->setChecked(b.rule.clamp.has_value());
  const widgets::VariationRange range = b.rule.clamp.value_or(widgets::VariationRange{-1.0, 1.0});
  auto* lo = spin("clampMin", range.min, -1e6, 1e6);
  auto* hi = spin("clampMax", range.max, -1e6, 1e6);
  fields_.push_back(checkField(clamp, [this, id] { return scene_.widgets.binding(id).rule.clamp.has_value(); }));
  auto clampOf = [this, id] { return scene_.widgets.binding(id).rule.clamp.value_or(widgets::VariationRange{-1.0, 1.0}); };
  fields_.push_back(spinField(lo, [clampOf] { return clampOf().min; }));
  fields_.push_back(spinField(hi, [clampOf] { return clampOf().max; }));
  auto apply = [this, id, clamp, lo, hi] {
    guarded([&] {
      widgets::ConversionRule rule = scene_.widgets.binding(id).rule;
      rule.clamp = clamp->isChecked() ? std::optional(widgets::VariationRange{lo->value(), hi->value()}) : std::nullopt;
      controller_.setRule(id, rule);
    });
  };
  connect(clamp, &QCheckBox::toggled, this, apply);
  connect(lo, &QDoubleSpinBox::valueChanged, this, [clamp, apply] { if (clamp->isChecked()) apply(); });
  connect(hi, &QDoubleSpinBox::valueChanged, this, [clamp, apply] { if (clamp->isChecked()) apply(); });
  form_->addRow(tr("Clamp"), clamp);
  form_->addRow(tr("Clamp min"), lo);
  form_->addRow(tr("Clamp max"), hi);
}

QLabel* PropertyPanel::addLabel(const QString& title, std::function<QString()> text) {
  auto* label = new QLabel(text());
  fields_.push_back(textField(label, std::move(text)));
  form_->addRow(title, label);
  return label;
}

void PropertyPanel::showCell(widgets::WidgetId id) {
  const auto& m = scene_.widgets;
  addLabel(tr("Cell"), [&m, id] { return qs(m.name(id)); });
  addLabel(tr("Kind"), [&m, id] { return qs(cellKindName(m.cellSpec(id).kind)); });
  addLabel(tr("Lattice"), [&m, id] { return qs(m.name(m.latticeOf(id))); });
  addLabel(tr("Points"), [&m, id] { return QString::number(m.cellIndices(id).size()); });
  addLabel(tr("Widgets"), [&m, id] { return QString::number(m.affinesOf(id).size()); });
}

void PropertyPanel::showObject(const std::string& name) {
  const scenes::SceneObject* object = scene_.findObject(name);
  if (object == nullptr) return;
  // The layout holds the object (layoutOf()): it exists whenever a field reads it.
  auto mesh = [this, name]() -> const scenes::MeshData& { return scene_.findObject(name)->mesh; };
  addLabel(tr("Object"), [name] { return qs(name); });
  addLabel(tr("Points"), [mesh] { return QString::number(mesh().points.rows()); });
  addLabel(tr("Triangles"), [mesh] { return QString::number(mesh().triangles.rows()); });
  addLabel(tr("Segments"), [mesh] { return QString::number(mesh().segments.rows()); });
  addLabel(tr("Deformed by"), [this, name] {
    QStringList lattices;
    for (widgets::WidgetId l : scene_.latticesDeforming(name)) lattices << qs(scene_.widgets.name(l));
    return lattices.isEmpty() ? tr("(nothing)") : lattices.join(", ");
  });
  // Looks (DisplaySettings): zebra stripes for surfaces; tube or line and a curvature comb for curves.
  auto setLook = [this, name](auto change) {
    guarded([&] {
      scenes::DisplaySettings look = scene_.findObject(name)->display;
      change(look);
      controller_.setDisplay({name}, {look});
    });
  };
  const scenes::DisplaySettings& d = object->display;
  auto shown = [this, name]() -> const scenes::DisplaySettings& { return scene_.findObject(name)->display; };
  if (object->mesh.triangles.rows() > 0) {
    auto* style = new QComboBox;
    style->setObjectName("surfaceStyle");
    style->addItems({tr("shaded"), tr("zebra stripes")});
    style->setCurrentIndex(d.surfaceStyle == scenes::SurfaceStyle::Zebra ? 1 : 0);
    fields_.push_back(comboField(style, [shown] { return shown().surfaceStyle == scenes::SurfaceStyle::Zebra ? 1 : 0; }));
    connect(style, &QComboBox::currentIndexChanged, this, [setLook](int index) {
      setLook([index](scenes::DisplaySettings& look) {
        look.surfaceStyle = index == 1 ? scenes::SurfaceStyle::Zebra : scenes::SurfaceStyle::Shaded;
      });
    });
    form_->addRow(tr("Surface"), style);
    auto* stripes = new QSpinBox;
    stripes->setObjectName("zebraStripes");
    stripes->setRange(1, 256);
    stripes->setValue(d.zebraStripes);
    stripes->setKeyboardTracking(false);
    stripes->setEnabled(d.surfaceStyle == scenes::SurfaceStyle::Zebra);
    fields_.push_back(intSpinField(stripes, [shown] { return shown().zebraStripes; }));
    fields_.push_back(enabledField(stripes, [shown] { return shown().surfaceStyle == scenes::SurfaceStyle::Zebra; }));
    connect(stripes, &QSpinBox::valueChanged, this,
            [setLook](int n) { setLook([n](scenes::DisplaySettings& look) { look.zebraStripes = n; }); });
    form_->addRow(tr("Stripes"), stripes);
  } else if (object->mesh.segments.rows() > 0) {
    auto* curve = new QComboBox;
    curve->setObjectName("curveStyle");
    curve->addItem(tr("tube"), static_cast<int>(scenes::CurveStyle::Tube));
    curve->addItem(tr("line"), static_cast<int>(scenes::CurveStyle::Line));
    curve->setCurrentIndex(curve->findData(static_cast<int>(d.curveStyle)));
    fields_.push_back(comboField(curve, [shown, curve] { return curve->findData(static_cast<int>(shown().curveStyle)); }));
    connect(curve, &QComboBox::currentIndexChanged, this, [setLook, curve](int index) {
      const auto chosen = static_cast<scenes::CurveStyle>(curve->itemData(index).toInt());
      setLook([chosen](scenes::DisplaySettings& look) { look.curveStyle = chosen; });
    });
    form_->addRow(tr("Curve"), curve);
    auto* comb = new QCheckBox(tr("curvature comb"));
    comb->setObjectName("curvatureComb");
    comb->setChecked(d.curvatureComb);
    fields_.push_back(checkField(comb, [shown] { return shown().curvatureComb; }));
    connect(comb, &QCheckBox::toggled, this,
            [setLook](bool on) { setLook([on](scenes::DisplaySettings& look) { look.curvatureComb = on; }); });
    form_->addRow(tr("Comb"), comb);
    auto* scale = spin("combScale", d.combScale, 0.001, 100.0, 3);
    scale->setSingleStep(0.01);
    scale->setEnabled(d.curvatureComb);
    fields_.push_back(spinField(scale, [shown] { return shown().combScale; }));
    fields_.push_back(enabledField(scale, [shown] { return shown().curvatureComb; }));
    connect(scale, &QDoubleSpinBox::valueChanged, this,
            [setLook](double v) { setLook([v](scenes::DisplaySettings& look) { look.combScale = v; }); });
    form_->addRow(tr("Comb scale"), scale);
  }
}

}  // namespace ffdkit::app
