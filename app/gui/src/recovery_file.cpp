#include "ffdkit/gui/recovery_file.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <fstream>
#include <iterator>

#include <signal.h>
#include <unistd.h>

#include <QStandardPaths>

#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/scenes/scene_file.h"

namespace ffdkit::app {
namespace {

namespace fs = std::filesystem;

// A process id is alive when signal 0 reaches it (or it exists but belongs to someone else).
bool processAlive(long pid) { return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM; }

// The parts of a scene a scene file holds, without the objects' points: a recovery write costs
// what the file costs, not a copy of every mesh.
scenes::Scene fileContent(const scenes::Scene& scene, const scenes::Camera& camera, const fs::path& origin) {
  scenes::Scene out;
  out.description = scene.description;
  out.widgets = scene.widgets;
  out.setAttachments(scene.attachments());
  out.setCamera(camera);
  out.setBackground(scene.background());
  for (const scenes::SceneObject& object : scene.objects()) {
    scenes::SceneObject copy;
    copy.id = object.id;  // the attachments hold ids
    copy.name = object.name;
    copy.source = object.source;
    copy.display = object.display;
    // The recovery file lives elsewhere: a mesh path relative to the document's folder would
    // no longer resolve.
    if (auto* file = std::get_if<scenes::MeshFileSource>(&copy.source); file && fs::path(file->path).is_relative())
      file->path = (origin.empty() ? fs::current_path() : fs::absolute(origin).parent_path()) / file->path;
    out.addObject(std::move(copy));
  }
  return out;
}

}  // namespace

fs::path RecoveryFile::defaultDirectory() {
  return fs::path(QStandardPaths::writableLocation(QStandardPaths::AppDataLocation).toStdString()) / "recovery";
}

RecoveryFile::RecoveryFile(fs::path directory) : directory_(std::move(directory)) {
  const std::string pid = std::to_string(::getpid());
  scene_ = directory_ / (pid + ".json");
  origin_ = directory_ / (pid + ".origin");
}

void RecoveryFile::write(const scenes::Scene& scene, const scenes::Camera& camera, const fs::path& origin) {
  fs::create_directories(directory_);
  // The origin first: a scene file never appears without it.
  meshio::writeFileAtomically(origin_, origin.empty() ? std::string() : fs::absolute(origin).string());
  // The app's own file, read back with the confinement lifted: its mesh paths are the document's.
  scenes::writeScene(scene_, fileContent(scene, camera, origin),
                     scenes::SceneWriteOptions{.confinement = meshio::PathConfinement{.allowOutside = true}});
}

void RecoveryFile::remove() noexcept {
  std::error_code ignored;
  fs::remove(scene_, ignored);
  fs::remove(origin_, ignored);
}

std::vector<RecoveredDocument> RecoveryFile::orphans(const fs::path& directory) {
  std::vector<RecoveredDocument> out;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(directory, error)) {
    const fs::path& file = entry.path();
    if (file.extension() != ".json") continue;
    const std::string stem = file.stem().string();
    long pid = 0;
    const auto [end, ec] = std::from_chars(stem.data(), stem.data() + stem.size(), pid);
    if (ec != std::errc() || end != stem.data() + stem.size() || pid <= 0) continue;
    if (pid == static_cast<long>(::getpid()) || processAlive(pid)) continue;
    RecoveredDocument document;
    document.scene = file;
    std::ifstream in(fs::path(file).replace_extension(".origin"));
    document.origin = std::string(std::istreambuf_iterator<char>(in), {});
    document.written = fs::last_write_time(file, error);
    if (error) continue;
    out.push_back(std::move(document));
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.written > b.written; });
  return out;
}

void RecoveryFile::discard(const RecoveredDocument& document) noexcept {
  std::error_code ignored;
  fs::remove(document.scene, ignored);
  fs::remove(fs::path(document.scene).replace_extension(".origin"), ignored);
}

}  // namespace ffdkit::app
