#include "surface_mapper.h"

#include <vtkCamera.h>
#include <vtkMath.h>
#include <vtkMatrix4x4.h>
#include <vtkObjectFactory.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtk_glew.h>

namespace ffdkit::app {

vtkStandardNewMacro(SurfaceMapper);

void SurfaceMapper::BuildBufferObjects(vtkRenderer* renderer, vtkActor* actor) {
  ++bufferBuilds_;
  vtkOpenGLPolyDataMapper::BuildBufferObjects(renderer, actor);
}

void SurfaceMapper::BuildIBO(vtkRenderer* renderer, vtkActor* actor, vtkPolyData* poly) {
  // BuildBufferObjects leaves the polydata's time in TempState; the index buffer's key must hold
  // only what the indices depend on (the cell arrays' times, the representation, the edge flags).
  TempState.Clear();
  vtkStateStorage before;
  before = IBOBuildState;
  vtkOpenGLPolyDataMapper::BuildIBO(renderer, actor, poly);
  if (before != IBOBuildState) ++indexBuilds_;
}

bool SurfaceMapper::cullsBackFaces(vtkRenderer* renderer, vtkActor* actor) {
  if (!closedSurface_ || !foldFree_) return false;
  vtkProperty* property = actor->GetProperty();
  if (property->GetOpacity() < 1.0 || actor->HasTranslucentPolygonalGeometry() ||
      property->GetFrontfaceCulling() || property->GetRepresentation() != VTK_SURFACE || property->GetEdgeVisibility() ||
      GetNumberOfClippingPlanes() > 0 || renderer->GetSelector() != nullptr)
    return false;
  if (actor->GetMatrix()->Determinant() <= 0.0) return false;  // a mirror turns front faces back
  const double* bounds = actor->GetBounds();
  if (bounds == nullptr || !vtkMath::AreBoundsInitialized(bounds)) return false;
  vtkCamera* camera = renderer->GetActiveCamera();
  double eye[3], direction[3];
  camera->GetPosition(eye);
  camera->GetDirectionOfProjection(direction);
  const double nearPlane = camera->GetClippingRange()[0];
  for (int corner = 0; corner < 8; ++corner) {
    const double p[3] = {bounds[corner & 1], bounds[2 + ((corner >> 1) & 1)], bounds[4 + ((corner >> 2) & 1)]};
    const double depth = (p[0] - eye[0]) * direction[0] + (p[1] - eye[1]) * direction[1] + (p[2] - eye[2]) * direction[2];
    if (!(depth > nearPlane)) return false;
  }
  return true;
}

void SurfaceMapper::RenderPieceDraw(vtkRenderer* renderer, vtkActor* actor) {
  if (!cullsBackFaces(renderer, actor)) {
    vtkOpenGLPolyDataMapper::RenderPieceDraw(renderer, actor);
    return;
  }
  ++culledDraws_;
  // vtkOpenGLProperty::Render set the property's culling (none) before the mapper draws; the next
  // actor's property sets its own again.
  vtkOpenGLState* state = static_cast<vtkOpenGLRenderWindow*>(renderer->GetRenderWindow())->GetState();
  state->vtkglCullFace(GL_BACK);
  state->vtkglEnable(GL_CULL_FACE);
  vtkOpenGLPolyDataMapper::RenderPieceDraw(renderer, actor);
  state->vtkglDisable(GL_CULL_FACE);
}

void SurfaceMapper::ComputeBounds() {
  vtkPolyData* input = GetInput();
  if (input != nullptr && input->GetPoints() != nullptr && input->GetNumberOfPoints() > 0)
    input->GetPoints()->GetBounds(Bounds);
  else
    vtkMath::UninitializeBounds(Bounds);
}

}  // namespace ffdkit::app
