#include "ffdkit/interaction/shape_guard.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "ffdkit/ffd/closed_surface.h"
#include "ffdkit/ffd/lattice.h"
#include "ffdkit/ffd/shape_constraints.h"

namespace ffdkit::app {

struct ShapeGuard::Kept {
  ShapeKeep keep;
  double volume = 0.0;                               // the volume kept (world units^3)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // the centre kept (world)
  bool closed = false;                               // a closed surface: the centre is the solid's centroid
};

struct ShapeGuard::Prepared {
  widgets::WidgetId lattice;
  std::uint64_t instance = 0, frameRevision = 0, meshRevision = 0;
  ShapeKeep keep;
  std::optional<ffd::Lattice> ffdLattice;  // the embedded lattice; its control points are set per step
  std::unique_ptr<ffd::ShapeConstraints> constraints;
};

ShapeGuard::ShapeGuard() = default;
ShapeGuard::~ShapeGuard() = default;
ShapeGuard::ShapeGuard(ShapeGuard&&) noexcept = default;
ShapeGuard& ShapeGuard::operator=(ShapeGuard&&) noexcept = default;

namespace {

const scenes::SceneObject& objectOf(const scenes::Scene& scene, scenes::ObjectId object) {
  const scenes::SceneObject* o = scene.findObject(object);
  if (o == nullptr) throw std::invalid_argument("Keep Volume / Keep Centre: no object with id " + std::to_string(object.value));
  return *o;
}

// The object's closed surface, or nullopt with the reason it is not one.
std::optional<ffd::ClosedSurface> closedSurface(const scenes::SceneObject& o, std::string* why) {
  if (o.mesh.triangles.rows() == 0) {
    *why = "it has no triangles (a curve or a point cloud encloses no volume)";
    return std::nullopt;
  }
  try {
    return ffd::ClosedSurface(ffd::TriangleMatrix(o.mesh.triangles), o.mesh.points.rows());
  } catch (const ffd::ConstraintError& e) {
    *why = std::string("it is not a closed surface: ") + e.what();
    return std::nullopt;
  }
}

}  // namespace

void ShapeGuard::setKeep(const scenes::Scene& scene, const scenes::SceneDeformer& deformer, scenes::ObjectId object,
                         ShapeKeep keep) {
  const scenes::SceneObject& o = objectOf(scene, object);
  prepared_.erase(object);
  if (!keep.any()) {
    kept_.erase(object);
    return;
  }
  Eigen::MatrixX3d points = o.mesh.points;
  try {
    points = deformer.points(object);  // the object as it is shown
  } catch (const std::invalid_argument&) {
  }
  std::string why;
  const std::optional<ffd::ClosedSurface> surface = closedSurface(o, &why);
  if (keep.volume && !surface) throw std::invalid_argument("Keep Volume: '" + o.name + "' encloses no volume: " + why);
  Kept k;
  k.keep = keep;
  k.closed = surface.has_value();
  if (keep.volume) {
    k.volume = ffd::enclosedVolume(points, *surface);
    if (!(std::abs(k.volume) > 0.0) || !std::isfinite(k.volume))
      throw std::invalid_argument("Keep Volume: '" + o.name + "' encloses a volume of " + std::to_string(k.volume));
  }
  if (keep.centre) {
    k.centre = points.colwise().mean().transpose();
    if (surface) try {
        k.centre = ffd::enclosedCentroid(points, *surface);
      } catch (const ffd::ConstraintError&) {
        k.closed = false;  // a closed surface enclosing no volume: the mean of its points
      }
  }
  kept_[object] = k;
  // The precompute now rather than at the first step of a drag (seconds for 10^6 vertices).
  if (const auto stages = scene.stagesDeforming(object); stages.size() == 1) {
    try {
      prepare(scene, object, stages.front());
    } catch (...) {
      kept_.erase(object);
      throw;
    }
  }
}

ShapeKeep ShapeGuard::keep(scenes::ObjectId object) const {
  const auto it = kept_.find(object);
  return it == kept_.end() ? ShapeKeep{} : it->second.keep;
}

double ShapeGuard::keptVolume(scenes::ObjectId object) const {
  const auto it = kept_.find(object);
  if (it == kept_.end() || !it->second.keep.volume)
    throw std::invalid_argument("Keep Volume is off for object " + std::to_string(object.value));
  return it->second.volume;
}

ShapeGuard::Prepared& ShapeGuard::prepare(const scenes::Scene& scene, scenes::ObjectId object, widgets::WidgetId lattice) {
  const scenes::SceneObject& o = objectOf(scene, object);
  const Kept& k = kept_.at(object);
  const auto& m = scene.widgets;
  std::unique_ptr<Prepared>& slot = prepared_[object];
  if (slot && slot->lattice == lattice && slot->instance == m.instance() && slot->frameRevision == m.frameRevision(lattice) &&
      slot->meshRevision == o.meshRevision && slot->keep == k.keep)
    return *slot;
  slot.reset();
  auto p = std::make_unique<Prepared>();
  p->lattice = lattice;
  p->instance = m.instance();
  p->frameRevision = m.frameRevision(lattice);
  p->meshRevision = o.meshRevision;
  p->keep = k.keep;
  p->ffdLattice.emplace(m.ffdLattice(lattice));
  p->constraints = std::make_unique<ffd::ShapeConstraints>(*p->ffdLattice, o.mesh.points);
  std::string why;
  const std::optional<ffd::ClosedSurface> surface = closedSurface(o, &why);
  try {
    if (k.keep.volume) {
      if (!surface) throw std::invalid_argument("Keep Volume: '" + o.name + "' encloses no volume: " + why);
      p->constraints->keepVolume(*surface, k.volume);
    }
    if (k.keep.centre) {
      if (k.closed && surface) p->constraints->keepCentroid(*surface, k.centre);
      else p->constraints->keepBarycentre(k.centre);
    }
  } catch (const ffd::ConstraintError& e) {
    throw std::invalid_argument("'" + o.name + "': " + e.what());
  }
  slot = std::move(p);
  return *slot;
}

std::vector<ShapeGuardStep> ShapeGuard::correct(scenes::Scene& scene, widgets::WidgetId lattice,
                                                const std::vector<bool>& free) {
  std::vector<ShapeGuardStep> steps;
  auto& m = scene.widgets;
  const Eigen::Index n = m.controlPoints(lattice).rows();
  if (static_cast<Eigen::Index>(free.size()) != n)
    throw std::invalid_argument("ShapeGuard::correct: " + std::to_string(free.size()) + " free flags for " +
                                std::to_string(n) + " control points");
  std::optional<std::string> correctedFirst;  // the object already corrected through this lattice
  for (const auto& [id, k] : kept_) {
    const scenes::SceneObject* o = scene.findObject(id);
    if (o == nullptr) continue;
    const std::vector<widgets::WidgetId> stages = scene.stagesDeforming(id);
    if (std::find(stages.begin(), stages.end(), lattice) == stages.end()) continue;
    ShapeGuardStep step;
    step.object = id;
    step.volumeChange = std::numeric_limits<double>::quiet_NaN();
    if (stages.size() != 1) {
      step.problem = "'" + o->name + "' is deformed by " + std::to_string(stages.size()) +
                     " lattices: its volume and centre are kept only when one lattice deforms it";
    } else if (correctedFirst) {
      step.problem = "'" + o->name + "' shares its lattice with '" + *correctedFirst +
                     "', whose volume and centre are kept: one kept object per lattice";
    } else {
      try {
        Prepared& p = prepare(scene, id, lattice);
        ffd::ControlMask mask(n, 3);
        for (Eigen::Index i = 0; i < n; ++i) mask.row(i).setConstant(free[static_cast<std::size_t>(i)]);
        p.constraints->setFreeControls(mask);
        p.ffdLattice->setControlPoints(m.controlPoints(lattice));
        // The weights as they are now (a weight typed since the keep was turned on): the
        // constraints follow them (ShapeConstraints::solve; the volume polynomial only while they
        // are the rest weights, else the volume is summed per vertex).
        if (const Eigen::VectorXd weights = m.weights(lattice); weights != p.ffdLattice->weights())
          p.ffdLattice->setWeights(weights);
        // A drag step's correction is small: the centroid's Jacobian of the first Newton step is
        // kept for the later ones (one pass over the vertices' gradients per drag step, not one
        // per Newton step).
        const ffd::ShapeSolveResult result =
            p.constraints->solve(*p.ffdLattice, {.jacobian = ffd::JacobianUpdate::FirstStep});
        step.iterations = result.iterations;
        if (k.keep.volume) step.volumeChange = (result.volume - k.volume) / std::abs(k.volume);
        if (!result.change.isZero(0.0)) m.setControlPoints(lattice, m.controlPoints(lattice) + result.change);
        correctedFirst = o->name;
      } catch (const std::exception& e) {
        step.problem = "'" + o->name + "': " + e.what();
      }
    }
    steps.push_back(std::move(step));
  }
  return steps;
}

void ShapeGuard::prune(const scenes::Scene& scene) {
  std::erase_if(kept_, [&](const auto& entry) { return scene.findObject(entry.first) == nullptr; });
  std::erase_if(prepared_, [&](const auto& entry) { return scene.findObject(entry.first) == nullptr; });
}

}  // namespace ffdkit::app
