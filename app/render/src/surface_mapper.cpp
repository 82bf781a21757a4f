#include "surface_mapper.h"

#include <vtkMath.h>
#include <vtkObjectFactory.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

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

void SurfaceMapper::ComputeBounds() {
  vtkPolyData* input = GetInput();
  if (input != nullptr && input->GetPoints() != nullptr && input->GetNumberOfPoints() > 0)
    input->GetPoints()->GetBounds(Bounds);
  else
    vtkMath::UninitializeBounds(Bounds);
}

}  // namespace ffdkit::app
