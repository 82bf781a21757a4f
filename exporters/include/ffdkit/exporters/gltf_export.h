#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/scenes/scene.h"

namespace ffdkit::exporters {

/// What a .glb holds (docs/export.md).
enum class GltfContent {
  Frame,  ///< the deformed meshes at one time: positions, normals, triangles / lines / points
  Morph,  ///< the undeformed meshes with one morph target per key; an animation drives the weights
  Skin    ///< the undeformed meshes skinned to the lattices' control points (translation-only joints)
};

/// How a key goes on to the next one (mirrors the scene's key interpolation).
enum class KeyInterpolation { Constant, Linear, Smooth };

/// The animation to export: the scene at any time and its keys. Until a scene carries keys, any
/// callback that sets a scene's state from a time will do.
struct AnimationSource {
  /// Sorted, distinct key times in seconds (morph: one target per key; skin: sampled at each).
  std::vector<double> keyTimes;
  /// Per key, the interpolation towards the next key (size keyTimes.size(); the last is unused).
  /// Empty: all Linear.
  std::vector<KeyInterpolation> interpolation;
  /// Per key (optional): some part of the scene holds over the segment that starts here and
  /// jumps at its end (a Constant channel among moving ones). The skin then gets a sample just
  /// before the next key, as for a Constant segment. Empty: only Constant segments hold.
  std::vector<bool> jumps;
  /// Skin: also sampled at every frame of [keyTimes.front(), keyTimes.back()] at this rate (> 0).
  double frameRate = 24.0;
  /// Sets `scene` to time t (keyed variations, frames and control points; bindings follow).
  /// Called on a copy of the exported scene, times in any order. Empty: the scene is static.
  std::function<void(scenes::Scene&, double t)> setTime;
};

/// What exportGltf writes and how.
struct GltfExportOptions {
  GltfContent content = GltfContent::Frame;  ///< a frame, morph targets or a skin
  double time = 0.0;     ///< Frame: the time of the frame (ignored without AnimationSource::setTime)
  bool normals = true;   ///< write NORMAL for triangle meshes (Morph: normal deltas per target too)
  /// Skin: joints per vertex, 4 (JOINTS_0 / WEIGHTS_0) or 8 (also JOINTS_1 / WEIGHTS_1).
  int joints = 4;
  /// Skin: when 4 joints exceed `tolerance`, use 8 instead of refusing.
  bool raiseJoints = true;
  /// Skin: the largest position error allowed (scene units) at any sampled time, measured
  /// against ffdkit's own deformation; exceeded (with 8 joints) -> GltfExportError, no file.
  double tolerance = 1e-3;
  bool durable = true;   ///< flush the file to disk before renaming it into place
};

/// The error of one sampled time (skin: per k; morph: the float32 rounding at the key).
struct GltfSampleError {
  double time = 0.0;  ///< the sampled time
  double error4 = 0.0;       ///< skin with 4 joints per vertex (morph / frame: the error of the file)
  double error8 = 0.0;       ///< skin with 8 joints per vertex
  double linearError = 0.0;  ///< skin with every weight kept: what no k removes
  std::string object;        ///< where the largest error of the chosen k is
  Eigen::Index vertex = -1;  ///< the vertex of the largest error (-1: none)
};

/// What exportGltf wrote.
struct GltfExportReport {
  GltfContent content = GltfContent::Frame;  ///< a frame, morph targets or a skin
  int objects = 0;  ///< meshes written
  Eigen::Index vertices = 0;  ///< vertices written, all meshes
  Eigen::Index triangles = 0;  ///< triangles written, all meshes
  int morphTargets = 0;        ///< Morph: per mesh
  std::string interpolation;   ///< Morph / Skin: the sampler's ("STEP" or "LINEAR"); "" for Frame
  int joints = 0;              ///< Skin: joint nodes (control points + the static joint)
  int k = 0;                   ///< Skin: joints per vertex written (4 or 8)
  double jointScale = 1.0;     ///< Skin: SkinBinding::jointScale
  std::vector<GltfSampleError> samples;  ///< per sampled time
  double maxError = 0.0;       ///< the largest position error of the file written (scene units)
  double sceneSize = 0.0;      ///< diagonal of the undeformed objects' bounding box (for scale)
  std::uintmax_t bytes = 0;    ///< size of the .glb
};

/// An export refused or failed: what, where, and what to try.
class GltfExportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Writes `scene` as binary glTF 2.0 to `out` / atomically to `path` (meshio/atomic_write.h).
/// Positions are float32 in the scene's world coordinates (no node transform); every object
/// with points is one mesh node named after it (triangles, else segments as LINES, else POINTS).
/// Measures every sampled time against ffdkit's exact deformation (SceneDeformer::finishGesture):
/// the report's errors are recomputed from the float32 values written, as a player computes them.
/// @throws GltfExportError for a refused skin (tolerance exceeded: the message names the time,
///   object, vertex, the error with 4 and 8 joints and with all weights), bad options, an
///   animation without keys or setTime; std::runtime_error when the file cannot be written;
///   ffd::LatticeError for a degenerate lattice.
GltfExportReport exportGltf(const scenes::Scene& scene, const AnimationSource& animation, std::ostream& out,
                            const GltfExportOptions& options = {});
GltfExportReport exportGltf(const scenes::Scene& scene, const AnimationSource& animation,
                            const std::filesystem::path& path, const GltfExportOptions& options = {});

std::string_view gltfContentName(GltfContent content);  ///< "frame", "morph", "skin"

/// The times a skin export samples the animation at (seconds, sorted, distinct as float32): its
/// keys, every frame between the first and the last key at AnimationSource::frameRate, and the
/// sample just before the end of each held segment. A check that must hold wherever the skin is
/// measured (the fold-over guard of `ffdkit-cli export --skin`) runs at these times.
/// @throws GltfExportError for an animation without keys or setTime, or unsorted key times.
std::vector<double> skinSampleTimes(const AnimationSource& animation);

}  // namespace ffdkit::exporters
