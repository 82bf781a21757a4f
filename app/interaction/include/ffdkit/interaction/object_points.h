#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/widgets/ray.h"
#include "ffdkit/widgets/widget_id.h"

namespace ffdkit::app {

/// A point (vertex) of a scene object: what direct manipulation grabs and pins.
struct ObjectPoint {
  scenes::ObjectId object;  ///< a rename keeps the point (and a pin on it)
  Eigen::Index vertex = 0;
  friend bool operator==(const ObjectPoint&, const ObjectPoint&) = default;
};

/// The object point under the ray, on the deformed objects (`deformed`): the nearest vertex of
/// the first visible triangle hit; for curves and point clouds the nearest vertex within
/// `tolerance` (world units) of the ray. nullopt when there is none.
std::optional<ObjectPoint> pickObjectPoint(const scenes::Scene& scene, const scenes::SceneDeformer& deformed,
                                           const widgets::Ray& ray, double tolerance);

/// Where the world point `point` is after the lattices `stages[0, count)` have deformed it (the
/// input of stage `count` of an object's pipeline, Scene::stagesDeforming).
Eigen::Vector3d pointBeforeStage(const scenes::Scene& scene, const std::vector<widgets::WidgetId>& stages,
                                 std::size_t count, const Eigen::Vector3d& point);

/// The weights w (one per control point of `lattice`) of a direct-manipulation drag with pins:
/// when the grabbed point moves by d (lattice-local), the least-norm control change
/// w * d^T (ffd::leastNormControlChange; Hsu, Hughes & Kaufman 1992 eqs. (4)-(6)) moves it by d
/// and each pin inside the lattice by 0 (`carryPins` false: they keep their place exactly,
/// as far as the constraints are independent) or by d too (`carryPins`: they move together).
/// Pins of other objects count when `lattice` deforms them; pins the lattice cannot move (not
/// deformed by it, or outside it) are left out; the grabbed point itself is never a pin.
/// @param grabbedParameters the grabbed point's parameters in the lattice (1 x 3).
Eigen::VectorXd pinnedDragWeights(const scenes::Scene& scene, widgets::WidgetId lattice,
                                  const Eigen::RowVector3d& grabbedParameters, const ObjectPoint& grabbed,
                                  const std::vector<ObjectPoint>& pins, bool carryPins);

}  // namespace ffdkit::app
