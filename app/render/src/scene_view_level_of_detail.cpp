// SceneView's level of detail (LevelOfDetail, object_proxy.h): while things move, a large shaded
// surface draws its proxy, and during a gesture the deformer evaluates it at the proxy's vertices.

#include "scene_view_impl.h"

#include <vtkFloatArray.h>
#include <vtkPointData.h>

#include "object_arrays.h"

namespace ffdkit::app {

// The proxy built with the actor and at each refresh, not at the first gesture (object_proxy.h).
void SceneView::Impl::prepareProxy(ObjectActor& entry, const scenes::SceneObject* object) {
  if (prepareObjectProxy(entry.proxy, lod, renderer, entry.actor, object, entry.pointCount, entry.display))
    ++stats.proxyBuilds;
}
// Draws `entry` as its proxy when things move and it is large enough; returns whether it did.
// Otherwise the object's own actor is shown.
bool SceneView::Impl::drawProxy(ObjectActor& entry, const scenes::Scene& scene, const scenes::SceneDeformer& deformed) {
  prepareProxy(entry, scene.findObject(entry.id));
  if (!(moving || deformed.inGesture()) || !entry.proxy) {
    if (entry.proxy && entry.proxy->shown()) entry.proxy->show(false);
    return false;
  }
  entry.proxy->show(true);
  if (entry.proxy->update(deformed, entry.id)) ++stats.proxyUpdates;
  return true;
}

void SceneView::setLevelOfDetail(const LevelOfDetail& lod) { impl_->lod = lod; }
const LevelOfDetail& SceneView::levelOfDetail() const { return impl_->lod; }
void SceneView::setMoving(bool moving) { impl_->moving = moving; }
scenes::EvaluationRequest SceneView::evaluationRequest(const scenes::Scene& scene, const scenes::SceneDeformer& deformed) {
  scenes::EvaluationRequest request;  // during a gesture, the objects drawn as proxies at their vertices only
  if (!deformed.inGesture() || !impl_->sameObjects(scene)) return request;  // refresh() builds actors from full points
  for (auto& entry : impl_->objects) {
    impl_->prepareProxy(entry, scene.findObject(entry.id));
    if (entry.proxy) {
      request.subsets[entry.id] = entry.proxy->vertices();
      continue;
    }
    // Drawn in full and following a one-control-point drag (gesture_normals.h): the next steps
    // read the motion only, and the deformer's delta passes over the full points may wait.
    auto* normals = vtkFloatArray::SafeDownCast(entry.polyData->GetPointData()->GetNormals());
    if (normals && !entry.comb && entry.gestureNormals.follows(deformed, entry.id, entry.polyData->GetPoints(), normals))
      request.followed.insert(entry.id);
  }
  return request;
}
bool SceneView::showsProxy(const std::string& object) const {
  for (const auto& entry : impl_->objects)
    if (entry.name == object) return entry.proxy && entry.proxy->shown();
  return false;
}
Eigen::MatrixX3d SceneView::objectPoints(const std::string& object) const {
  for (const auto& entry : impl_->objects)
    if (entry.name == object) return object_arrays::worldPoints(entry.polyData->GetPoints(), entry.origin);
  return {};
}

}  // namespace ffdkit::app
