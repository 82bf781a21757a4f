// The interaction controller, direct manipulation (Hsu, Hughes & Kaufman 1992): a drag on a point of an object
// moves its lattice by the least-norm change (HHK 1992), with pinned points held.
#include "ffdkit/interaction/interaction_controller.h"

#include <stdexcept>

#include "ffdkit/interaction/object_points.h"
#include "ffdkit/ffd/direct_manipulation.h"
#include "ffdkit/ffd/embedding.h"

namespace ffdkit::app {

using widgets::WidgetId;

std::optional<std::string> InteractionController::pressObject(const widgets::Ray& ray, double tolerance, bool carryPins) {
  if (dragging_) cancel();
  deformer_.evaluate(scene_);  // the points under the ray as they are now (a change may wait for a frame)
  const Eigen::Vector3d dir = ray.direction.normalized();
  const std::optional<ObjectPoint> best = objectPointAt(ray, tolerance);
  if (!best) return std::nullopt;
  const auto& [id, vertex] = *best;
  const std::string& name = scene_.objectName(id);
  const std::vector<WidgetId> stages = scene_.stagesDeforming(id);
  if (stages.empty()) throw std::invalid_argument("'" + name + "' is not deformed by a lattice: attach one to drag its points");
  const Eigen::Vector3d own = scene_.findObject(id)->mesh.points.row(vertex).transpose();
  // From the last stage back: the first lattice whose input holds the point moves it; a later
  // one that does not hold it must leave it alone (identity outside policy).
  for (std::size_t k = stages.size(); k-- > 0;) {
    const ffd::Lattice lattice = scene_.widgets.ffdLattice(stages[k]);
    const Eigen::Vector3d input = pointBeforeStage(scene_, stages, k, own);
    const ffd::Embedding e = ffd::embed(lattice, input.transpose());
    if (e.status(0) == ffd::PointStatus::Inside) {
      ObjectGrab g;
      g.object = id;
      g.vertex = vertex;
      g.lattice = stages[k];
      g.weights = pinnedDragWeights(scene_, stages[k], e.parameters().row(0), *best, pins_, carryPins);
      g.worldToLocal = lattice.frame().linear().inverse();
      g.grab = deformer_.points(id).row(vertex).transpose();
      g.normal = dir;
      g.controlStart = scene_.widgets.controlPoints(stages[k]);
      g.basis = ffd::basisWeights(lattice, e.parameters().row(0).transpose());
      objectGrab_ = std::move(g);
      dragStart_ = scene_.widgets.captureState();
      recordDragStart();
      dragLattice_ = stages[k];
      dragging_ = true;
      deformer_.beginGesture(dragLattice_);
      notify();
      return name;
    }
    if (lattice.outsidePolicy().kind != ffd::OutsidePolicy::Kind::Identity)
      throw std::invalid_argument("point " + std::to_string(vertex) + " of '" + name + "' is outside lattice '" +
                                  scene_.widgets.name(stages[k]) +
                                  "', whose outside policy moves it: direct manipulation needs a point inside");
  }
  throw std::invalid_argument("point " + std::to_string(vertex) + " of '" + name +
                              "' is outside every lattice deforming it: nothing can move it");
}

void InteractionController::togglePin(const ObjectPoint& point) {
  const scenes::SceneObject* object = scene_.findObject(point.object);
  if (object == nullptr || point.vertex < 0 || point.vertex >= object->mesh.points.rows())
    throw std::invalid_argument("no point " + std::to_string(point.vertex) + " of object " + scenes::toString(point.object) + " to pin");
  if (std::erase(pins_, point) == 0) pins_.push_back(point);
  notify();
}

void InteractionController::clearPins() {
  pins_.clear();
  notify();
}

}  // namespace ffdkit::app
