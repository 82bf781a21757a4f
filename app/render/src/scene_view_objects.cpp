// SceneView's object actors: one per visible object of the scene, with its normals, zebra
// coordinates, curvature comb and level-of-detail proxy.

#include "scene_view_impl.h"

#include <algorithm>

#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkTubeFilter.h>

#include "closed_surface.h"
#include "ffdkit/render/curvature_comb.h"
#include "object_arrays.h"
#include "surface_mapper.h"

namespace ffdkit::app {

namespace {

using namespace scene_view_shapes;

}  // namespace

void SceneView::Impl::clearObjects() {
  for (auto& o : objects) {
    renderer->RemoveActor(o.actor);
    if (o.comb) renderer->RemoveActor(o.comb);
  }
  objects.clear();
}

void SceneView::Impl::buildObjects(const scenes::Scene& scene, const scenes::SceneDeformer& deformed) {
  clearObjects();
  for (const auto& object : scene.objects()) {
    if (!object.display.visible) continue;
    ObjectActor entry;
    entry.id = object.id;
    entry.name = object.name;
    const Eigen::MatrixX3d& points = deformed.points(object.id);
    entry.pointCount = points.rows();
    entry.pointsRevision = deformed.revision(object.id);
    entry.restLo = object.mesh.points.rows() > 0 ? Eigen::Vector3d(object.mesh.points.colwise().minCoeff().transpose())
                                                 : Eigen::Vector3d::Zero();
    entry.restHi = object.mesh.points.rows() > 0 ? Eigen::Vector3d(object.mesh.points.colwise().maxCoeff().transpose())
                                                 : Eigen::Vector3d::Zero();
    entry.display = object.display;
    entry.origin = 0.5 * (entry.restLo + entry.restHi);  // of its own points: the same in every view
    entry.polyData = object_arrays::objectPolyData(object.mesh, points, entry.origin);  // float32, 32-bit cells
    const bool zebra = object.display.surfaceStyle == scenes::SurfaceStyle::Zebra && object.mesh.triangles.rows() > 0;
    constexpr double kCurveLineWidth = 2.0;  // pixels, DisplaySettings::curveStyle
    const bool curveLine = object.display.curveStyle == scenes::CurveStyle::Line && object.mesh.triangles.rows() == 0 &&
                           object.mesh.segments.rows() > 0;
    vtkNew<SurfaceMapper> mapper;  // surface_mapper.h: no index buffer or cell bounds per frame
    if (object.mesh.triangles.rows() > 0) {
      vtkNew<vtkFloatArray> normals;  // smooth shading of the deformed surface
      entry.vertexFaces = vertexFaces(object.mesh.triangles, points.rows());
      // Of the rest points: the lattices' verdicts (outward_faces.h) say whether the deformation keeps it.
      mapper->setClosedSurface(closedOutwardSurface(object.mesh.points, object.mesh.triangles, entry.vertexFaces));
      entry.gestureNormals.update(deformed, object.id, object.mesh.triangles, entry.vertexFaces, points, entry.origin,
                                  entry.faceNormals, entry.polyData->GetPoints(), normals);
      entry.polyData->GetPointData()->SetNormals(normals);
      if (zebra) {
        vtkNew<vtkFloatArray> tcoords;
        updateZebraCoordinates(tcoords, normals, object.display.zebraDirection, object.display.zebraStripes);
        entry.polyData->GetPointData()->SetTCoords(tcoords);
      }
      mapper->SetInputData(entry.polyData);
    } else if (object.mesh.segments.rows() > 0) {
      if (curveLine) {
        // Curves as lines: the polyline itself (unlit, set below), the exact points drawn.
        mapper->SetInputData(entry.polyData);
      } else {
        // Curves as shaded tubes, thick enough to read at any zoom of the object.
        const double diagonal = (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
        vtkNew<vtkTubeFilter> tubes;
        tubes->SetInputData(entry.polyData);
        tubes->SetRadius(std::max(1e-6, 0.006 * diagonal));
        tubes->SetNumberOfSides(10);
        tubes->CappingOn();
        mapper->SetInputConnection(tubes->GetOutputPort());
      }
      if (object.display.curvatureComb) {
        entry.chains = segmentChains(object.mesh.segments, points.rows());
        entry.combFactor = combFactor(entry.chains, object.mesh.points, object.display.combScale,
                                      (entry.restHi - entry.restLo).norm());
        vtkNew<vtkPolyDataMapper> combMapper;
        combMapper->SetInputData(combPolyData(entry.chains, points, entry.combFactor));
        entry.comb = vtkSmartPointer<vtkActor>::New();
        entry.comb->SetMapper(combMapper);
        entry.comb->GetProperty()->SetColor(kCombColour.x(), kCombColour.y(), kCombColour.z());
        entry.comb->GetProperty()->SetLighting(false);
        entry.comb->GetProperty()->SetLineWidth(1.5);
        renderer->AddActor(entry.comb);
      }
    } else {
      mapper->SetInputData(entry.polyData);
    }
    entry.actor = vtkSmartPointer<vtkActor>::New();
    entry.actor->SetPosition(entry.origin.data());  // where the float points are relative to
    entry.actor->GetProperty()->SetLineWidth(3.0);
    entry.actor->GetProperty()->SetPointSize(4.0);
    entry.actor->SetMapper(mapper);
    entry.actor->GetProperty()->SetColor(object.display.color.x(), object.display.color.y(), object.display.color.z());
    entry.actor->GetProperty()->SetOpacity(object.display.opacity);
    entry.actor->GetProperty()->SetSpecular(0.2);
    entry.actor->GetProperty()->SetSpecularPower(30);
    if (zebra) {  // unlit stripes: the texture's colours exactly
      entry.actor->SetTexture(zebraTexture());
      entry.actor->GetProperty()->SetColor(1.0, 1.0, 1.0);
      entry.actor->GetProperty()->SetLighting(false);
    }
    if (curveLine) {  // unlit: the object's colour exactly, at any orientation of the line
      entry.actor->GetProperty()->SetLighting(false);
      entry.actor->GetProperty()->SetLineWidth(kCurveLineWidth);
    }
    renderer->AddActor(entry.actor);
    prepareProxy(entry, &object);  // level of detail: the proxy at load, not at the first gesture
    updateKeepsOutward(entry, scene.widgets);
    objects.push_back(std::move(entry));
    ++stats.objectBuilds;
  }
  updateFoldFree();
}

void SceneView::Impl::updateFoldFree() {
  for (auto& entry : objects) updateFoldFree(entry);
}

void SceneView::Impl::updateFoldFree(ObjectActor& entry) {
  if (auto* mapper = SurfaceMapper::SafeDownCast(entry.actor->GetMapper()))
    mapper->setFoldFree(highlights.foldTints.empty() && entry.keepsOutward);
}

void SceneView::Impl::updateKeepsOutward(ObjectActor& entry, const widgets::WidgetModel& model) {
  auto* mapper = SurfaceMapper::SafeDownCast(entry.actor->GetMapper());
  if (mapper == nullptr || !mapper->closedSurface()) return;  // never culled: nothing to ask
  entry.keepsOutward = outwardFaces.keepsOutward(model, entry.restLo, entry.restHi, highlights.certified);
  stats.foldChecks = outwardFaces.checks();
  updateFoldFree(entry);
}

// True when the drawn objects are the scene's visible objects with the same point counts.
bool SceneView::Impl::sameObjects(const scenes::Scene& scene) const {
  std::size_t n = 0;
  for (const auto& object : scene.objects()) {
    if (!object.display.visible) continue;
    if (n >= objects.size() || objects[n].id != object.id ||
        objects[n].pointCount != object.mesh.points.rows() || !(objects[n].display == object.display))
      return false;
    ++n;
  }
  return n == objects.size();
}

Eigen::MatrixX3f SceneView::objectNormals(const std::string& object) const {
  for (const auto& entry : impl_->objects) {
    if (entry.name != object) continue;
    auto* normals = vtkFloatArray::SafeDownCast(entry.polyData->GetPointData()->GetNormals());
    if (!normals) break;
    Eigen::MatrixX3f out(normals->GetNumberOfTuples(), 3);
    for (Eigen::Index i = 0; i < out.rows(); ++i)
      for (int c = 0; c < 3; ++c) out(i, c) = normals->GetPointer(0)[3 * i + c];
    return out;
  }
  return {};
}

SceneViewMemory SceneView::objectMemory() const {
  SceneViewMemory memory;
  for (const auto& entry : impl_->objects) {
    memory.vertices += entry.pointCount;
    memory.bytes += std::size_t(entry.polyData->GetActualMemorySize()) * 1024;  // VTK reports KiB
    memory.bytes += sizeof(int) * (entry.vertexFaces.start.capacity() + entry.vertexFaces.faces.capacity());
    memory.bytes += sizeof(Eigen::Vector3f) * entry.faceNormals.capacity();
    memory.bytes += entry.gestureNormals.memoryBytes();
    if (entry.proxy) memory.bytes += entry.proxy->memoryBytes();
  }
  return memory;
}

}  // namespace ffdkit::app
