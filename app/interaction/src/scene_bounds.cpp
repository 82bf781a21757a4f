#include "ffdkit/interaction/scene_bounds.h"

namespace ffdkit::app {

namespace {
void extend(Eigen::AlignedBox3d& box, const Eigen::MatrixX3d& points) {
  if (points.rows() == 0) return;
  box.extend(Eigen::Vector3d(points.colwise().minCoeff().transpose()));
  box.extend(Eigen::Vector3d(points.colwise().maxCoeff().transpose()));
}
}  // namespace

Eigen::AlignedBox3d selectionBounds(const scenes::Scene& scene, const scenes::SceneDeformer& deformed,
                                    const std::vector<widgets::WidgetId>& widgets,
                                    const std::vector<std::string>& objects) {
  Eigen::AlignedBox3d box;
  const widgets::WidgetModel& model = scene.widgets;
  for (widgets::WidgetId id : widgets) {
    if (!model.contains(id)) continue;
    switch (model.type(id)) {
      case widgets::WidgetType::Lattice: extend(box, model.worldControlPoints(id)); break;
      case widgets::WidgetType::Cell: extend(box, model.cellWorldPoints(id)); break;
      case widgets::WidgetType::Affine: {
        const widgets::WidgetFrame f = model.affineFrame(id);
        box.extend(f.frame.translation() - Eigen::Vector3d::Constant(f.size));
        box.extend(f.frame.translation() + Eigen::Vector3d::Constant(f.size));
        break;
      }
    }
  }
  for (const std::string& name : objects)
    if (scene.findObject(name) != nullptr) extend(box, deformed.points(name));
  return box;
}

Eigen::AlignedBox3d sceneBounds(const scenes::Scene& scene, const scenes::SceneDeformer& deformed) {
  std::vector<std::string> objects;
  for (const scenes::SceneObject& o : scene.objects()) objects.push_back(o.name);
  std::vector<widgets::WidgetId> widgets;
  for (auto type : {widgets::WidgetType::Lattice, widgets::WidgetType::Affine})
    for (widgets::WidgetId id : scene.widgets.widgets(type)) widgets.push_back(id);
  return selectionBounds(scene, deformed, widgets, objects);
}

}  // namespace ffdkit::app
