#pragma once
// File > Export glTF...: a dialog for exporters::GltfExportOptions (what to write, joints,
// tolerance, the path), then the export and its report. The export itself is
// exporters::exportGltf, the same call as ffdkit-cli export.

#include <QDialog>

#include "ffdkit/exporters/gltf_export.h"
#include "ffdkit/scenes/scene.h"

class QComboBox;
class QDoubleSpinBox;
class QLineEdit;

namespace ffdkit::app {

/// The options dialog (objectName "gltfExportDialog"; children "content", "joints",
/// "tolerance", "path", "browse").
class GltfExportDialog : public QDialog {
 public:
  explicit GltfExportDialog(QWidget* parent);
  exporters::GltfExportOptions options() const;
  QString path() const;

 private:
  QComboBox* content_;
  QComboBox* joints_;
  QDoubleSpinBox* tolerance_;
  QLineEdit* path_;
};

/// Asks for the options and the path, exports `scene` (as shown for a frame; through its keys for
/// morph targets and skins) and shows the report, or the refusal / error in a message box.
/// @return the report of a written file, or nothing (cancelled, refused, failed).
std::optional<exporters::GltfExportReport> exportGltfInteractively(QWidget* parent, const scenes::Scene& scene);

}  // namespace ffdkit::app
