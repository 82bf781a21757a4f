// The app's read preferences, kept between sessions: the read limits (File > Read Limits...:
// meshio::ReadLimits) and the confinement opt-out (File > Allow Files Outside a Scene's Folder:
// meshio::PathConfinement). Open, Open Recent, Import Mesh, Open Widget File, a dropped file and
// recovery all read with the options made here, as ffdkit-cli's --max-memory, --max-points and
// --allow-outside make them.
#pragma once

#include <string>

#include <QDialog>

#include "ffdkit/meshio/mesh_io.h"
#include "ffdkit/meshio/path_confinement.h"
#include "ffdkit/meshio/read_limits.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/scenes/widget_file.h"

class QLabel;
class QLineEdit;
class QMenu;

namespace ffdkit::app {

/// QSettings keys: the opt-out (bool, default false), the limits (bytes and points, as numbers;
/// absent or unusable: the defaults of meshio::ReadLimits).
inline constexpr const char* kAllowOutsideKey = "allowFilesOutsideSceneFolder";
inline constexpr const char* kMaxMemoryKey = "readLimits/maxMemoryBytes";
inline constexpr const char* kMaxPointsKey = "readLimits/maxPoints";

/// The limits of the next read.
meshio::ReadLimits readLimits();
/// Keeps `limits` for the next reads (and sessions).
void setReadLimits(const meshio::ReadLimits& limits);
/// The confinement rule of the next read (the preference; before it existed the same choice was
/// kept as "allowMeshesOutsideSceneFolder", which is still honoured when it is all there is).
meshio::PathConfinement pathConfinement();

/// The options of the next read of each kind, from the preferences.
scenes::SceneReadOptions sceneReadOptions();
meshio::MeshReadOptions meshReadOptions();
scenes::WidgetReadOptions widgetReadOptions();

/// A read's error as the app shows it: where the library's message names the CLI's options
/// ("(--max-memory)", "--allow-outside"), the app's menu items instead.
std::string readErrorText(const std::string& what);

/// File > Read Limits... (objectName "readLimitsDialog"): "maxMemory" and "maxPoints" fields
/// take what the CLI takes ("512M", "8GiB"; "2M", "100000"); OK keeps them, a malformed one
/// keeps the dialog open and says why ("problem" label); "defaults" restores the defaults.
class ReadLimitsDialog : public QDialog {
 public:
  explicit ReadLimitsDialog(QWidget* parent);
  void accept() override;

 private:
  QLineEdit* maxMemory_;
  QLineEdit* maxPoints_;
  QLabel* problem_;
};

/// Adds File > Allow Files Outside a Scene's Folder (checkable, objectName "actionAllowOutside")
/// and File > Read Limits... (objectName "actionReadLimits") to `file`.
void addReadPreferenceActions(QMenu* file, QWidget* dialogParent);

}  // namespace ffdkit::app
