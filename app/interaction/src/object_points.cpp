#include "ffdkit/interaction/object_points.h"

#include <algorithm>
#include <limits>

#include "ffdkit/ffd/direct_manipulation.h"
#include "ffdkit/ffd/embedding.h"
#include "ffdkit/ffd/pipeline.h"

namespace ffdkit::app {

std::optional<ObjectPoint> pickObjectPoint(const scenes::Scene& scene, const scenes::SceneDeformer& deformed,
                                           const widgets::Ray& ray, double tolerance) {
  const Eigen::Vector3d dir = ray.direction.normalized();
  std::optional<ObjectPoint> best;
  double bestT = std::numeric_limits<double>::infinity();
  for (const scenes::SceneObject& object : scene.objects()) {
    if (!object.display.visible) continue;
    const Eigen::MatrixX3d& points = deformed.points(object.id);
    const Eigen::MatrixX3i& triangles = object.mesh.triangles;
    if (triangles.rows() > 0) {
      for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
        const Eigen::Vector3d a = points.row(triangles(t, 0)).transpose(), b = points.row(triangles(t, 1)).transpose(),
                              c = points.row(triangles(t, 2)).transpose();
        const auto hit = widgets::intersectTriangle(ray, a, b, c);
        if (!hit || *hit >= bestT) continue;
        bestT = *hit;
        const Eigen::Vector3d p = ray.at(*hit);
        int corner = 0;
        for (int k = 1; k < 3; ++k)
          if ((points.row(triangles(t, k)).transpose() - p).norm() < (points.row(triangles(t, corner)).transpose() - p).norm())
            corner = k;
        best = ObjectPoint{object.id, static_cast<Eigen::Index>(triangles(t, corner))};
      }
    } else {
      for (Eigen::Index i = 0; i < points.rows(); ++i) {
        const Eigen::Vector3d v = points.row(i).transpose() - ray.origin;
        const double t = v.dot(dir);
        if (t < 0.0 || t >= bestT || (v - t * dir).norm() > tolerance) continue;
        bestT = t;
        best = ObjectPoint{object.id, i};
      }
    }
  }
  return best;
}

Eigen::Vector3d pointBeforeStage(const scenes::Scene& scene, const std::vector<widgets::WidgetId>& stages,
                                 std::size_t count, const Eigen::Vector3d& point) {
  if (count == 0) return point;
  ffd::Pipeline pipeline(point.transpose());
  for (std::size_t i = 0; i < count; ++i)
    pipeline.addLattice(scene.widgets.ffdLattice(stages[i]), std::nullopt, static_cast<int>(i));
  return pipeline.update().row(0).transpose();
}

Eigen::VectorXd pinnedDragWeights(const scenes::Scene& scene, widgets::WidgetId latticeId,
                                  const Eigen::RowVector3d& grabbedParameters, const ObjectPoint& grabbed,
                                  const std::vector<ObjectPoint>& pins, bool carryPins) {
  const ffd::Lattice lattice = scene.widgets.ffdLattice(latticeId);
  std::vector<Eigen::RowVector3d> parameters{grabbedParameters};
  std::vector<double> moves{1.0};
  for (const ObjectPoint& pin : pins) {
    const scenes::SceneObject* object = scene.findObject(pin.object);
    if (pin == grabbed || object == nullptr || pin.vertex >= object->mesh.points.rows()) continue;
    const std::vector<widgets::WidgetId> stages = scene.stagesDeforming(pin.object);
    const auto stage = std::find(stages.begin(), stages.end(), latticeId);
    if (stage == stages.end()) continue;  // this lattice does not deform it
    const Eigen::Vector3d input = pointBeforeStage(scene, stages, static_cast<std::size_t>(stage - stages.begin()),
                                                   object->mesh.points.row(pin.vertex).transpose());
    const ffd::Embedding e = ffd::embed(lattice, input.transpose());
    if (e.status(0) != ffd::PointStatus::Inside) continue;
    parameters.push_back(e.parameters().row(0));
    moves.push_back(carryPins ? 1.0 : 0.0);
  }
  Eigen::MatrixX3d uvw(static_cast<Eigen::Index>(parameters.size()), 3);
  Eigen::MatrixX3d displacements = Eigen::MatrixX3d::Zero(uvw.rows(), 3);
  for (Eigen::Index r = 0; r < uvw.rows(); ++r) {
    uvw.row(r) = parameters[static_cast<std::size_t>(r)];
    displacements(r, 0) = moves[static_cast<std::size_t>(r)];
  }
  // The change is linear in the displacement: its x column for a unit x move is the weight vector.
  return ffd::leastNormControlChange(lattice, uvw, displacements).col(0);
}

}  // namespace ffdkit::app
