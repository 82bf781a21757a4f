#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "ffdkit/scenes/scene.h"

namespace ffdkit::app {

/// A recovery file another ffdkit process left behind (it crashed or was killed).
struct RecoveredDocument {
  std::filesystem::path scene;   ///< the autosaved scene file
  std::filesystem::path origin;  ///< the document's own file; empty for a scene never saved
  std::filesystem::file_time_type written;
};

/// Autosave for crash recovery: this process's open document, written atomically to
/// `<directory>/<pid>.json` (and the document's own path to `<pid>.origin`). A clean exit
/// removes it; the next start finds the files of processes that are gone and offers them.
/// The default directory is Qt's writable application-data location (`recovery/` under
/// QStandardPaths::AppDataLocation, e.g. ~/.local/share/ffdkit/recovery).
class RecoveryFile {
 public:
  static std::filesystem::path defaultDirectory();

  explicit RecoveryFile(std::filesystem::path directory = defaultDirectory());

  /// Writes `scene` seen through `camera` (widgets inline, mesh paths made absolute against
  /// `origin`'s folder, no meshes copied) atomically; `origin` is where the document lives
  /// (empty for a scene never saved).
  /// @throws scenes::SceneFileError / std::runtime_error if the folder cannot be written.
  void write(const scenes::Scene& scene, const scenes::Camera& camera, const std::filesystem::path& origin);
  /// Removes this process's files (nothing to recover). Never throws.
  void remove() noexcept;
  const std::filesystem::path& path() const { return scene_; }

  /// Recovery files of processes no longer running, newest first. Unreadable entries are
  /// skipped (a half-written temporary file is never a `<pid>.json`).
  static std::vector<RecoveredDocument> orphans(const std::filesystem::path& directory = defaultDirectory());
  /// Deletes an orphan's files (after it was restored or declined). Never throws.
  static void discard(const RecoveredDocument& document) noexcept;

 private:
  std::filesystem::path directory_;
  std::filesystem::path scene_;
  std::filesystem::path origin_;
};

}  // namespace ffdkit::app
