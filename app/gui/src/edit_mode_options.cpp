// The edit mode's options: soft selection (O, Alt+O, the falloffs, the radius during G / R / S)
// and Keep Volume / Keep Centre (EditController::shapeGuard), with their status-bar report.
#include <QActionGroup>
#include <QApplication>
#include <QSignalBlocker>
#include <QStatusBar>
#include <QToolButton>

#include <algorithm>
#include <cmath>

#include "edit_mode.h"

namespace ffdkit::app {

namespace {

QString qs(const std::string& s) { return QString::fromStdString(s); }

QString capitalised(std::string_view name) {
  QString text = QString::fromLatin1(name.data(), static_cast<int>(name.size()));
  text[0] = text[0].toUpper();
  return text;
}

}  // namespace

void EditModeInput::addSoftSelectionActions(QMenu* parent) {
  QMenu* menu = parent->addMenu(tr("S&oft Selection"));
  menu->setObjectName("menuSoftSelection");
  softAction_ = addAction(menu, tr("&Soft Selection"), "actionSoftSelection", true, {});
  softAction_->setCheckable(true);
  softAction_->setToolTip(tr("G / R / S also move the points near the selection, each by the falloff of its distance"));
  connect(softAction_, &QAction::triggered, this, [this](bool on) {
    SoftSelection soft = p_.edit->softSelection();
    soft.enabled = on;
    p_.edit->setSoftSelection(soft);
    p_.status->say(on ? tr("Soft selection on (%1, radius %2): during G / R / S the wheel or PageUp / PageDown sets "
                           "the radius")
                            .arg(qs(std::string(falloffName(soft.falloff))))
                            .arg(soft.radius, 0, 'g', 3)
                      : tr("Soft selection off"),
                   5000);
  });
  connectedAction_ = addAction(menu, tr("&Connected Only"), "actionSoftConnected", true, {});
  connectedAction_->setCheckable(true);
  connectedAction_->setToolTip(tr("Soft selection measures distances along the lattice's grid lines"));
  connect(connectedAction_, &QAction::triggered, this, [this](bool on) {
    SoftSelection soft = p_.edit->softSelection();
    soft.connectedOnly = on;
    p_.edit->setSoftSelection(soft);
    p_.status->say(on ? tr("Soft selection: distances along the grid (connected only)")
                      : tr("Soft selection: straight distances"),
                   5000);
  });
  menu->addSeparator();
  auto* falloffs = new QActionGroup(this);
  for (Falloff falloff : kFalloffs) {
    const std::string name = std::string("actionFalloff") + capitalised(falloffName(falloff)).toStdString();
    QAction* a = addAction(menu, capitalised(falloffName(falloff)), "", false, [this, falloff] {
      SoftSelection soft = p_.edit->softSelection();
      soft.falloff = falloff;
      p_.edit->setSoftSelection(soft);
    });
    a->setObjectName(QString::fromStdString(name));
    a->setCheckable(true);
    a->setChecked(falloff == p_.edit->softSelection().falloff);
    falloffs->addAction(a);
  }
}

void EditModeInput::scaleSoftRadius(double factor) {
  p_.edit->scaleSoftRadius(factor);
  p_.status->say(tr("Soft selection radius %1").arg(p_.edit->softSelection().radius, 0, 'g', 3));
}

void EditModeInput::addShapeGuardActions(QMenu* menu) {
  menu->addSeparator();
  keepVolume_ = addAction(menu, tr("Keep &Volume"), "actionKeepVolume", false, {});
  keepVolume_->setToolTip(tr("Every drag and transform keeps the volume of the selected object (closed surfaces)"));
  keepCentre_ = addAction(menu, tr("Keep C&entre"), "actionKeepCentre", false, {});
  keepCentre_->setToolTip(tr("Every drag and transform keeps the centre of the selected object"));
  for (QAction* a : {keepVolume_, keepCentre_}) {
    a->setCheckable(true);
    const bool volume = a == keepVolume_;
    connect(a, &QAction::triggered, this, [this, volume](bool on) {
      try {
        setKeep(volume, on);
      } catch (const std::exception& e) {
        syncKeepActions();
        p_.sayError(e.what());
        QApplication::beep();
      }
    });
    // On the status bar beside the volume change it reports, as text buttons.
    auto* button = new QToolButton;
    button->setDefaultAction(a);
    button->setToolButtonStyle(Qt::ToolButtonTextOnly);
    button->setAutoRaise(true);
    button->setObjectName(volume ? "keepVolumeButton" : "keepCentreButton");
    p_.window->statusBar()->addPermanentWidget(button);
  }
}

std::vector<scenes::ObjectId> EditModeInput::keptTargets() const {
  if (p_.selectedObjects)
    if (std::vector<scenes::ObjectId> selected = p_.selectedObjects(); !selected.empty()) return selected;
  const scenes::Scene& scene = *p_.scene;
  std::vector<scenes::ObjectId> out;
  if (p_.edit->editing())
    for (const scenes::SceneObject& o : scene.objects()) {
      const auto stages = scene.stagesDeforming(o.id);
      if (std::find(stages.begin(), stages.end(), p_.edit->lattice()) != stages.end()) out.push_back(o.id);
    }
  if (out.empty() && scene.objects().size() == 1) out.push_back(scene.objects().front().id);
  if (out.empty()) throw std::invalid_argument("select the object whose volume or centre to keep (outliner)");
  return out;
}

void EditModeInput::setKeep(bool volume, bool on) {
  ShapeGuard& guard = p_.edit->shapeGuard();
  QStringList names;
  for (scenes::ObjectId id : keptTargets()) {
    ShapeKeep keep = guard.keep(id);
    (volume ? keep.volume : keep.centre) = on;
    p_.edit->setKeep(id, keep);  // throws for an open surface
    names << qs(p_.scene->objectName(id));
  }
  syncKeepActions();
  const QString what = volume ? tr("volume") : tr("centre");
  p_.status->say(on ? tr("Keeping the %1 of %2 while its lattice moves").arg(what, names.join(", "))
                    : tr("No longer keeping the %1 of %2").arg(what, names.join(", ")),
                 5000);
}

void EditModeInput::syncKeepActions() {
  if (!keepVolume_) return;
  bool volume = false, centre = false;
  try {
    const std::vector<scenes::ObjectId> targets = keptTargets();
    volume = centre = true;
    for (scenes::ObjectId id : targets) {
      const ShapeKeep keep = p_.edit->shapeGuard().keep(id);
      volume = volume && keep.volume;
      centre = centre && keep.centre;
    }
  } catch (const std::invalid_argument&) {
  }
  const QSignalBlocker a(keepVolume_), b(keepCentre_);
  keepVolume_->setChecked(volume);
  keepCentre_->setChecked(centre);
}

QString EditModeInput::guardText() const {
  QStringList parts;
  // The edit mode's transform, else the controller's drag (a glyph, a cell, a handle, an object point).
  const std::vector<ShapeGuardStep>& steps = p_.edit->transforming() ? p_.edit->guardSteps() : p_.controller->guardSteps();
  for (const ShapeGuardStep& step : steps) {
    const QString name = p_.scene->findObject(step.object) ? qs(p_.scene->objectName(step.object)) : QString();
    if (!step.problem.empty()) parts << tr("not kept: %1").arg(qs(step.problem));
    else if (std::isnan(step.volumeChange)) parts << tr("%1: centre kept").arg(name);
    else parts << tr("%1: volume change %2").arg(name).arg(step.volumeChange, 0, 'e', 1);
  }
  return parts.join("; ");
}

}  // namespace ffdkit::app
