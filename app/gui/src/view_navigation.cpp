#include "view_navigation.h"

#include <QAction>
#include <QMenu>
#include <QSettings>

#include "ffdkit/render/scene_view.h"
#include "ffdkit/viewhost/vtk_view_widget.h"

namespace ffdkit::app {

ViewNavigation::ViewNavigation(VtkViewWidget* view, SceneView& sceneView, std::function<Eigen::AlignedBox3d()> selection,
                               std::function<Eigen::AlignedBox3d()> everything, QObject* parent)
    : QObject(parent), view_(view), sceneView_(sceneView), selection_(std::move(selection)),
      everything_(std::move(everything)) {}

void ViewNavigation::addActions(QMenu* viewMenu) {
  auto add = [&](const QString& text, const char* name, auto slot) {
    QAction* a = viewMenu->addAction(text);
    a->setObjectName(name);
    connect(a, &QAction::triggered, this, slot);
    return a;
  };
  add(tr("&Frame Selected"), "actionFrameSelected", [this] {
    const Eigen::AlignedBox3d box = selection_();
    frameBox(box.isEmpty() ? everything_() : box);  // nothing selected: everything
  });
  add(tr("Frame &All"), "actionFrameAll", [this] { frameBox(everything_()); });
  QMenu* views = viewMenu->addMenu(tr("&Axis Views"));
  const struct {
    const char* text;
    const char* name;
    ViewPreset preset;
  } presets[] = {{"&Front", "actionViewFront", ViewPreset::Front}, {"&Back", "actionViewBack", ViewPreset::Back},
                 {"&Right", "actionViewRight", ViewPreset::Right}, {"&Left", "actionViewLeft", ViewPreset::Left},
                 {"&Top", "actionViewTop", ViewPreset::Top},       {"B&ottom", "actionViewBottom", ViewPreset::Bottom}};
  for (const auto& p : presets) {
    QAction* a = views->addAction(tr(p.text));
    a->setObjectName(p.name);
    connect(a, &QAction::triggered, this, [this, preset = p.preset] { setCamera(viewFrom(sceneView_.viewCamera(), preset)); });
  }
  orthographic_ = add(tr("&Orthographic"), "actionOrthographic", [this] {
    const ViewCamera now = sceneView_.viewCamera();
    if (now.parallel != orthographic_->isChecked()) setCamera(toggledProjection(now));
  });
  orthographic_->setCheckable(true);
  // A preference, kept between sessions: a turntable by default (no roll), VTK's trackball if asked.
  trackball_ = add(tr("Trac&kball Orbit"), "actionTrackballOrbit",
                   [this] { QSettings().setValue(kOrbitStyleKey, trackball_->isChecked() ? "trackball" : "turntable"); });
  trackball_->setCheckable(true);
  trackball_->setChecked(QSettings().value(kOrbitStyleKey, "turntable").toString() == "trackball");
}

OrbitStyle ViewNavigation::orbitStyle() const {
  return trackball_ != nullptr && trackball_->isChecked() ? OrbitStyle::Trackball : OrbitStyle::Turntable;
}

void ViewNavigation::beginOrbit(QPoint at) {
  orbiting_ = true;
  last_ = at;
}

bool ViewNavigation::orbitTo(QPoint at) {
  if (!orbiting_) return false;
  const QPoint delta = at - last_;
  last_ = at;
  OrbitOptions options;
  options.style = orbitStyle();
  setCamera(orbit(sceneView_.viewCamera(), delta.x(), delta.y(), options));
  return true;
}

void ViewNavigation::frameBox(const Eigen::AlignedBox3d& box) {
  if (box.isEmpty()) return;
  FrameOptions options;
  options.aspect = view_->height() > 0 ? static_cast<double>(view_->width()) / view_->height() : 1.0;
  setCamera(frame(sceneView_.viewCamera(), box, options));
}

void ViewNavigation::setCamera(const ViewCamera& camera) {
  sceneView_.setViewCamera(camera);
  if (orthographic_ != nullptr) orthographic_->setChecked(camera.parallel);
  view_->requestRender();
}

}  // namespace ffdkit::app
