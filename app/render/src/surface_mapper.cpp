#include "surface_mapper.h"

#include <vtkMath.h>
#include <vtkObjectFactory.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

namespace ffdkit::app {

vtkStandardNewMacro(SurfaceMapper);

void SurfaceMapper::BuildIBO(vtkRenderer* renderer, vtkActor* actor, vtkPolyData* poly) {
  // BuildBufferObjects leaves the polydata's time in TempState; the index buffer's key must hold
  // only what the indices depend on (the cell arrays' times, the representation, the edge flags).
  TempState.Clear();
  vtkOpenGLPolyDataMapper::BuildIBO(renderer, actor, poly);
}

void SurfaceMapper::ComputeBounds() {
  vtkPolyData* input = GetInput();
  if (input != nullptr && input->GetPoints() != nullptr && input->GetNumberOfPoints() > 0)
    input->GetPoints()->GetBounds(Bounds);
  else
    vtkMath::UninitializeBounds(Bounds);
}

}  // namespace ffdkit::app
