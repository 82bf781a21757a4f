// The 3D view's navigation in the window: orbiting on a left-drag over empty space (turntable,
// or trackball as a preference), frame selected / frame all, the keypad's axis views and the
// orthographic toggle, as View menu actions. The camera maths is headless
// (ffdkit/interaction/camera_navigation.h); this only turns pointer moves and actions into it.
#pragma once

#include <functional>

#include <Eigen/Geometry>
#include <QObject>
#include <QPoint>

#include "ffdkit/interaction/camera_navigation.h"

class QAction;
class QMenu;

namespace ffdkit::app {

class SceneView;
class VtkViewWidget;

/// QSettings key of the orbit preference: "turntable" (default) or "trackball".
inline constexpr const char* kOrbitStyleKey = "orbitStyle";

class ViewNavigation : public QObject {
  Q_OBJECT

 public:
  /// `selection` gives the world box of what is selected (empty: nothing), `everything` the
  /// scene's (scene_bounds.h); both are called when the action runs.
  ViewNavigation(VtkViewWidget* view, SceneView& sceneView, std::function<Eigen::AlignedBox3d()> selection,
                 std::function<Eigen::AlignedBox3d()> everything, QObject* parent);

  /// Adds the View menu's actions (object names actionFrameSelected, actionFrameAll,
  /// actionViewFront / Back / Right / Left / Top / Bottom, actionOrthographic,
  /// actionTrackballOrbit); their keys come from keyboard_shortcuts.
  void addActions(QMenu* viewMenu);

  /// A left press on empty space (or a lattice point) starts an orbit at `at` (view pixels).
  void beginOrbit(QPoint at);
  /// Orbits by the pointer's move since the last call. @return false when no orbit is under way.
  bool orbitTo(QPoint at);
  void endOrbit() { orbiting_ = false; }

  OrbitStyle orbitStyle() const;
  /// Shows `box` whole (frame()), the view's aspect taken from the widget. Nothing for an empty box.
  void frameBox(const Eigen::AlignedBox3d& box);

 private:
  void setCamera(const ViewCamera& camera);

  VtkViewWidget* view_;
  SceneView& sceneView_;
  std::function<Eigen::AlignedBox3d()> selection_, everything_;
  QAction* orthographic_ = nullptr;
  QAction* trackball_ = nullptr;
  bool orbiting_ = false;
  QPoint last_;
};

}  // namespace ffdkit::app
