#include "shape_guard.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <stdexcept>

#include "ffdkit/ffd/closed_surface.h"
#include "ffdkit/ffd/fold_check.h"
#include "ffdkit/ffd/shape_constraints.h"

namespace ffdkit::cli {

namespace {

std::string formatted(const char* pattern, double a, double b, double c) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, pattern, a, b, c);
  return buffer;
}

}  // namespace

bool ShapeGuardRequest::keeps(const std::string& object) const {
  return std::find(keepVolume.begin(), keepVolume.end(), object) != keepVolume.end() ||
         std::find(keepCentre.begin(), keepCentre.end(), object) != keepCentre.end();
}

ShapeGuardRequest parseShapeGuard(const Args& args) {
  ShapeGuardRequest r;
  r.keepVolume = args.values("keep-volume");
  r.keepCentre = args.values("keep-centre");
  if (auto mode = args.value("fold-check")) {
    if (*mode == "error") {
      r.foldCheck = FoldCheckMode::Error;
    } else if (*mode == "warn") {
      r.foldCheck = FoldCheckMode::Warn;
    } else if (*mode == "off") {
      r.foldCheck = FoldCheckMode::Off;
    } else {
      throw UsageError("--fold-check must be error, warn or off; got '" + *mode + "'");
    }
  }
  return r;
}

std::vector<OptionSpec> shapeGuardOptions() {
  return {{"keep-volume", '\0', "OBJECT",
           "restore the volume OBJECT's closed surface enclosed before deforming (to 1e-12; a correction lattice)", true},
          {"keep-centre", '\0', "OBJECT",
           "restore OBJECT's centre (solid centroid of a closed surface, else the mean of its points)", true},
          {"fold-check", '\0', "MODE",
           "error, warn (default) or off: a lattice whose map folds space (certified bound) fails or warns"}};
}

namespace {

// "(i, j, k)" of the first `most` cells with verdict `which` (flat index cu + cells_u (cv + cells_v cw)),
// "..." after them when there are more.
std::string firstCells(const ffd::FoldCheckResult& result, ffd::CellFolding which, int most = 3) {
  std::string text;
  int listed = 0;
  for (std::size_t c = 0; c < result.cells.size(); ++c) {
    if (result.cells[c] != which) continue;
    if (listed == most) return text + ", ...";
    const std::size_t cu = std::size_t(result.cellCounts[0]), cv = std::size_t(result.cellCounts[1]);
    text += std::string(listed ? ", " : "") + "(" + std::to_string(c % cu) + ", " + std::to_string(c / cu % cv) + ", " +
            std::to_string(c / cu / cv) + ")";
    ++listed;
  }
  return text;
}

}  // namespace

std::vector<std::string> foldFindings(const widgets::WidgetModel& model) {
  std::vector<std::string> findings;
  for (auto id : model.pipelineOrder()) {
    const ffd::Lattice lattice = model.ffdLattice(id);
    const ffd::FoldCheckResult result = ffd::checkFolding(lattice);
    if (result.certifiedPositive()) continue;
    const std::string total = std::to_string(result.cells.size());
    std::string line = "lattice " + model.name(id);
    if (result.foldsCount > 0) {
      line += " folds in " + std::to_string(result.foldsCount) + " of " + total + " cells";
      for (std::size_t c = 0; c < result.cells.size(); ++c)
        if (result.cells[c] == ffd::CellFolding::Folds) {
          const Eigen::Vector3d w = result.witness[c];
          char value[48];
          std::snprintf(value, sizeof value, " (det J = %.3g", lattice.jacobian(w).determinant() * result.orientation);
          line += value + formatted(" at u,v,w = %.4g, %.4g, %.4g)", w.x(), w.y(), w.z());
          break;
        }
      line += ": cells " + firstCells(result, ffd::CellFolding::Folds);
      if (result.unknownCount > 0)
        line += "; " + std::to_string(result.unknownCount) + " unknown: cells " +
                firstCells(result, ffd::CellFolding::Unknown);
    } else {
      line += ": " + std::to_string(result.unknownCount) + " of " + total +
              " cells not certified free of fold-over (unknown): cells " + firstCells(result, ffd::CellFolding::Unknown);
    }
    findings.push_back(line);
  }
  return findings;
}

std::vector<std::string> skinFoldFindings(const scenes::Scene& scene, const exporters::AnimationSource& animation) {
  if (animation.keyTimes.empty() || !animation.setTime) return foldFindings(scene.widgets);
  // Every time the skin is sampled at, not only the keys: bindings and rotations carry the
  // lattices along paths that can fold between two keys that do not.
  const std::vector<double> times = exporters::skinSampleTimes(animation);
  std::vector<std::string> findings;
  std::vector<double> folding;  // the sampled times with a finding
  scenes::Scene at = scene;     // one copy, set to each time in turn
  for (double t : times) {
    animation.setTime(at, t);
    const std::vector<std::string> lines = foldFindings(at.widgets);
    if (lines.empty()) continue;
    folding.push_back(t);
    if (folding.size() > 1) continue;  // the first time in full, the others counted
    for (const auto& line : lines) findings.push_back(formatted("at t = %g s: ", t, 0, 0) + line);
  }
  if (folding.size() > 1)
    findings.push_back(std::to_string(folding.size()) + " of the " + std::to_string(times.size()) +
                       " sampled times fold or are not certified" + formatted(" (t = %g s to %g s)", folding.front(), folding.back(), 0));
  return findings;
}

void checkFoldsBeforeDeform(const widgets::WidgetModel& model, FoldCheckMode mode, Console& console) {
  if (mode == FoldCheckMode::Off) return;
  const std::vector<std::string> findings = foldFindings(model);
  if (findings.empty()) return;
  if (mode == FoldCheckMode::Error) {
    std::string message = "--fold-check error: the deformation folds space over itself:";
    for (const auto& f : findings) message += "\n  " + f;
    throw std::runtime_error(message + "\n(--fold-check warn writes it anyway)");
  }
  for (const auto& f : findings) console.warn(f);
}

void restoreShape(const std::string& object, const scenes::MeshData& rest, Eigen::MatrixX3d& deformed, bool volume,
                  bool centre, Console& console) {
  if (!volume && !centre) return;
  if (deformed.rows() == 0) throw std::runtime_error("--keep-volume/--keep-centre: object '" + object + "' has no points");
  const Eigen::Vector3d lo = deformed.colwise().minCoeff().transpose(), hi = deformed.colwise().maxCoeff().transpose();
  const double pad = 0.05 * std::max((hi - lo).norm(), 1e-12);
  ffd::BoxLatticeOptions options;
  options.boxMin = lo - Eigen::Vector3d::Constant(pad);
  options.boxMax = hi + Eigen::Vector3d::Constant(pad);
  ffd::Lattice lattice = ffd::makeBoxLattice(options);
  ffd::ShapeConstraints constraints(lattice, deformed);
  std::optional<ffd::ClosedSurface> surface;
  const auto closed = [&]() -> const ffd::ClosedSurface& {
    if (!surface) surface.emplace(ffd::TriangleMatrix(rest.triangles), rest.points.rows());
    return *surface;
  };
  double restVolume = 0.0;
  try {
    if (volume) {
      restVolume = ffd::enclosedVolume(rest.points, closed());
      constraints.keepVolume(closed(), restVolume, ffd::VolumeEvaluation::PerVertex);  // one solve: no precompute
    }
    if (centre) {
      bool isClosed = rest.triangles.rows() > 0;
      if (isClosed) {
        try {
          closed();
        } catch (const ffd::ConstraintError&) {
          isClosed = false;
        }
      }
      if (isClosed)
        constraints.keepCentroid(closed(), ffd::enclosedCentroid(rest.points, closed()));
      else
        constraints.keepBarycentre(rest.points.colwise().mean().transpose());
    }
    const ffd::ShapeSolveResult result = constraints.solve(lattice);
    deformed = constraints.deformedPoints();
    std::string line = "object " + object + ":";
    if (volume)
      line += formatted(" volume kept at %.12g (relative error %.2g, %.0f Newton steps)", restVolume,
                        result.volumeRelativeError, double(result.iterations));
    if (centre) line += std::string(volume ? ";" : "") + " centre kept";
    console.say(line);
  } catch (const ffd::ConstraintError& e) {
    throw std::runtime_error("object '" + object + "': " + e.what());
  }
}

}  // namespace ffdkit::cli
