// ffdkit-cli: the shape guards of `deform` (--keep-volume, --keep-centre, --fold-check) and the
// fold-over report of `info` and `validate`.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "args.h"
#include "console.h"
#include "ffdkit/exporters/gltf_export.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::cli {

enum class FoldCheckMode { Error, Warn, Off };

/// The guard options of one deform run.
struct ShapeGuardRequest {
  std::vector<std::string> keepVolume;  ///< objects whose enclosed volume is restored
  std::vector<std::string> keepCentre;  ///< objects whose centre (solid centroid, else mean) is restored
  FoldCheckMode foldCheck = FoldCheckMode::Warn;
  bool keeps(const std::string& object) const;
};

/// @throws UsageError for a --fold-check value other than error, warn, off.
ShapeGuardRequest parseShapeGuard(const Args& args);
std::vector<OptionSpec> shapeGuardOptions();

/// One line per lattice of the model that is not certified free of fold-over (ffd::checkFolding),
/// with the counts and the first three cells (u, v, w cell indices) of each verdict:
/// "lattice L0 folds in 2 of 27 cells (det J = -0.12 at u,v,w = 0.25, 0.5, 0.5): cells (0, 1, 2),
/// (1, 1, 2); 1 unknown: cells (2, 2, 2)" or "lattice L0: 3 of 27 cells not certified free of
/// fold-over (unknown): cells (...)". Empty when every lattice is certified positive.
std::vector<std::string> foldFindings(const widgets::WidgetModel& model);

/// foldFindings of the scene's widgets at every time a skin export samples `animation`
/// (exporters::skinSampleTimes: keys and frames): the first time that folds in full (each line
/// prefixed "at t = 1.5 s: "), then a line counting the sampled times that fold and their span
/// when there are more; of the scene as it is when the animation has no keys or no setTime.
std::vector<std::string> skinFoldFindings(const scenes::Scene& scene, const exporters::AnimationSource& animation);

/// --fold-check before a deform: Error throws std::runtime_error with the findings, Warn prints
/// them as warnings, Off does nothing.
void checkFoldsBeforeDeform(const widgets::WidgetModel& model, FoldCheckMode mode, Console& console);

/// Restores the volume and/or centre of one deformed object with a correction lattice: a 4x4x4
/// cubic B-spline box fitted around the deformed points (5% of the diagonal on every side), whose
/// least-norm control change meets the rest object's volume (to 1e-12 relative, Newton on the
/// Lagrange system, ffd::ShapeConstraints) and its centre (the solid's centroid for a closed
/// surface, else the mean of the points).
/// @param rest      the object before deformation (points and triangles).
/// @param deformed  its deformed points, corrected in place.
/// @throws std::runtime_error naming the object when --keep-volume meets an open surface or the
///         constraints cannot be met.
void restoreShape(const std::string& object, const scenes::MeshData& rest, Eigen::MatrixX3d& deformed, bool volume,
                  bool centre, Console& console);

}  // namespace ffdkit::cli
