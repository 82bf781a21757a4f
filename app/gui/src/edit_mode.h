#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <QAction>
#include <QKeyEvent>
#include <QLabel>
#include <QMainWindow>
#include <QMenu>
#include <QObject>
#include <QPoint>
#include <QRubberBand>
#include <QToolBar>

#include "ffdkit/interaction/edit_controller.h"
#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/render/scene_view.h"
#include "ffdkit/viewhost/vtk_view_widget.h"
#include "ffdkit/scenes/scene.h"
#include "status_line.h"

namespace ffdkit::app {

/// The Qt side of a lattice's edit mode and of group transforms (EditController holds the
/// logic): the actions (Tab: Edit Lattice Points; A, Alt+A, Ctrl+I, B; G, R, S; pivot; Make
/// Cell), the view's keys and mouse while editing or transforming (an event filter on the view
/// that sees events before the window's), the box's rubber band, the view's context menu and a
/// selection count in the status bar. It maps keys and pointers to EditController calls only.
class EditModeInput : public QObject {
  Q_OBJECT

 public:
  /// What it works with; all must outlive it.
  struct Parts {
    QMainWindow* window = nullptr;
    VtkViewWidget* view = nullptr;
    SceneView* sceneView = nullptr;
    StatusLine* status = nullptr;
    const scenes::Scene* scene = nullptr;
    InteractionController* controller = nullptr;
    EditController* edit = nullptr;
    std::function<void(const std::string&)> sayError;  ///< a refusal as the user reads it
    std::function<widgets::Ray(const QPoint&)> rayAt;   ///< view pixel -> world ray
    std::function<double()> tolerance;                  ///< pick tolerance (world units)
    std::function<void()> redraw;                       ///< the window's redraw of the model and highlights
    /// The objects selected in the outliner (Keep Volume / Keep Centre act on them).
    std::function<std::vector<scenes::ObjectId>()> selectedObjects;
    /// Shows the edit mode's selected points in the property panel (their weight field).
    std::function<void()> showProperties;
  };
  /// Adds its actions to `widgetsMenu` (Make Cell), a new Select menu and `toolbar`, and filters
  /// the view's events.
  EditModeInput(Parts parts, QMenu* widgetsMenu, QToolBar* toolbar);

  /// Leaves the edit mode (a new scene).
  void leave();
  /// Unchecks the Edit Mode toggle (and leaves the mode) when EditController::editing() ended
  /// behind its back (an undo removed or resized the lattice). The window calls it on every
  /// model change.
  void syncEditToggle();
  bool eventFilter(QObject* watched, QEvent* event) override;
  /// The shape guard's report of the last step of the transform or drag in progress
  /// ("sphere1: volume change 2.0e-16"), or "".
  QString guardText() const;

 private:
  /// A menu action; with `viewKeys`, its keys (from keyboard_shortcuts.cpp) act in the view only.
  QAction* addAction(QMenu* menu, const QString& text, const char* name, bool viewKeys, std::function<void()> slot);
  void toggleEditMode(bool on);
  void beginModal(TransformMode mode);
  void makeCell(std::optional<widgets::CellKind> kind);
  void changed();
  /// Soft selection's menu (O, Alt+O, the falloffs) in `menu`.
  void addSoftSelectionActions(QMenu* menu);
  /// Keep Volume and Keep Centre in `menu` and as buttons on the status bar.
  void addShapeGuardActions(QMenu* menu);
  /// The objects Keep Volume / Keep Centre act on: the selected ones, else those the edited
  /// lattice deforms, else the scene's only object. @throws std::invalid_argument for none.
  std::vector<scenes::ObjectId> keptTargets() const;
  /// Turns Keep Volume (`volume`) or Keep Centre on or off for keptTargets().
  void setKeep(bool volume, bool on);
  /// Checks Keep Volume / Keep Centre when every target object keeps it.
  void syncKeepActions();
  /// Grows (factor > 1) or shrinks the soft selection's radius during a transform.
  void scaleSoftRadius(double factor);
  void finishBox(const QPoint& end, Qt::KeyboardModifiers modifiers);
  Eigen::Vector3d viewDirection() const;
  /// The action of this object whose keys (keyboard_shortcuts.cpp) the event is, or null.
  QAction* viewActionFor(const QKeyEvent& event) const;
  /// A value typed during a drag: of a handle of EditController's transformer, or of the
  /// InteractionController (a glyph or one widget's transformer handle).
  bool typeIntoDrag(const QKeyEvent* event);
  Parts p_;
  QAction* editAction_ = nullptr;
  QAction* softAction_ = nullptr;       ///< Soft Selection (O)
  QAction* connectedAction_ = nullptr;  ///< Soft Selection: Connected Only (Alt+O)
  QAction* keepVolume_ = nullptr;
  QAction* keepCentre_ = nullptr;
  std::vector<QAction*> viewActions_;  ///< the actions whose keys act in the view
  QMenu* cellMenu_ = nullptr;
  QMenu* selectMenu_ = nullptr;
  QLabel* count_ = nullptr;
  QRubberBand* band_ = nullptr;
  QPoint lastPos_;
  bool havePos_ = false;
  std::optional<QPoint> boxFrom_;  ///< a box select being dragged
  bool boxArmed_ = false;          ///< B pressed: the next left press starts a box even on a point
  bool entering_ = false;          ///< toggleEditMode is entering the mode
  TypedValue dragTyped_;           ///< typed during a glyph or handle drag
  std::optional<QPoint> rightAt_;  ///< a right press in the edit mode (a click opens the context menu)
};

}  // namespace ffdkit::app
