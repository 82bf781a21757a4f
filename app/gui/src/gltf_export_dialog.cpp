#include "gltf_export_dialog.h"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QMessageBox>
#include <QPushButton>

#include "ffdkit/exporters/scene_animation.h"

namespace ffdkit::app {

GltfExportDialog::GltfExportDialog(QWidget* parent) : QDialog(parent) {
  setObjectName("gltfExportDialog");
  setWindowTitle(tr("Export glTF"));
  content_ = new QComboBox(this);
  content_->setObjectName("content");
  content_->addItem(tr("Deformed meshes as shown"));
  content_->addItem(tr("Animation as morph targets (one per key)"));
  content_->addItem(tr("Animation as a skin on the lattices' control points"));
  joints_ = new QComboBox(this);
  joints_->setObjectName("joints");
  joints_->addItem(tr("4 (8 if the tolerance needs it)"), 4);
  joints_->addItem(tr("8"), 8);
  tolerance_ = new QDoubleSpinBox(this);
  tolerance_->setObjectName("tolerance");
  tolerance_->setDecimals(6);
  tolerance_->setRange(0.0, 1e6);
  tolerance_->setValue(exporters::GltfExportOptions{}.tolerance);
  path_ = new QLineEdit(this);
  path_->setObjectName("path");
  auto* browse = new QPushButton(tr("Browse..."), this);
  browse->setObjectName("browse");
  connect(browse, &QPushButton::clicked, this, [this] {
    const QString chosen = QFileDialog::getSaveFileName(this, tr("Export glTF"), path_->text(), tr("Binary glTF (*.glb)"));
    if (!chosen.isEmpty()) path_->setText(chosen);
  });
  auto* pathRow = new QHBoxLayout;
  pathRow->addWidget(path_);
  pathRow->addWidget(browse);
  auto* form = new QFormLayout(this);
  form->addRow(tr("Export"), content_);
  form->addRow(tr("Skin joints per vertex"), joints_);
  form->addRow(tr("Skin tolerance"), tolerance_);
  form->addRow(tr("File"), pathRow);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  form->addRow(buttons);
  const auto skinOnly = [this] {
    const bool skin = content_->currentIndex() == 2;
    joints_->setEnabled(skin);
    tolerance_->setEnabled(skin);
  };
  connect(content_, &QComboBox::currentIndexChanged, this, skinOnly);
  skinOnly();
}

exporters::GltfExportOptions GltfExportDialog::options() const {
  exporters::GltfExportOptions options;
  options.content = static_cast<exporters::GltfContent>(content_->currentIndex());
  options.joints = joints_->currentData().toInt();
  options.raiseJoints = options.joints == 4;
  options.tolerance = tolerance_->value();
  return options;
}

QString GltfExportDialog::path() const { return path_->text(); }

std::optional<exporters::GltfExportReport> exportGltfInteractively(QWidget* parent, const scenes::Scene& scene) {
  GltfExportDialog dialog(parent);
  if (dialog.exec() != QDialog::Accepted || dialog.path().isEmpty()) return std::nullopt;
  const exporters::GltfExportOptions options = dialog.options();
  try {
    // A frame is the scene as shown; morph targets and skins play the scene's keys.
    const exporters::AnimationSource animation =
        options.content == exporters::GltfContent::Frame ? exporters::AnimationSource{} : exporters::sceneAnimation(scene);
    const exporters::GltfExportReport report = exporters::exportGltf(scene, animation, dialog.path().toStdString(), options);
    QString text = QObject::tr("Wrote %1 (%2 bytes).").arg(dialog.path()).arg(report.bytes);
    if (report.content == exporters::GltfContent::Skin)
      text += QObject::tr("\nSkin: %1 joints, %2 per vertex; largest position error %3 over %4 sampled times.")
                  .arg(report.joints).arg(report.k).arg(report.maxError, 0, 'g', 3).arg(report.samples.size());
    else
      text += QObject::tr("\nLargest position error %1 (float32).").arg(report.maxError, 0, 'g', 3);
    QMessageBox::information(parent, QObject::tr("Export glTF"), text);
    return report;
  } catch (const std::exception& e) {
    QMessageBox::critical(parent, QObject::tr("Export glTF"), QString::fromStdString(e.what()));
    return std::nullopt;
  }
}

}  // namespace ffdkit::app
