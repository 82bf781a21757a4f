#pragma once

#include <filesystem>
#include <memory>

#include <QMainWindow>

#include "ffdkit/scenes/scene.h"

namespace ffdkit::app {

class VtkViewWidget;

/// The application window: the 3D view of the current scene, menus and a status bar.
class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  explicit MainWindow(QWidget* parent = nullptr);
  ~MainWindow() override;

  /// Loads a scene file (or a sample-scene folder) and shows it.
  /// @throws scenes::SceneFileError if the file cannot be read; the current scene stays.
  void openScene(const std::filesystem::path& path);

  /// Shows `scene` (replacing the current one).
  void setScene(scenes::Scene scene);
  const scenes::Scene& scene() const;

  VtkViewWidget* view() const;

 private:
  void openSceneDialog();

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ffdkit::app
