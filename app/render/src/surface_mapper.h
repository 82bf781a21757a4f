#pragma once

// The mapper of the view's large surfaces (private to ffdkit::render: the objects' actors and their
// level-of-detail proxies). VTK's OpenGL polydata mapper, with two costs of a frame after the
// points moved taken out; neither changes what is drawn:
//  - the triangles' index buffer is built again only when the triangles change. VTK 9.1 rebuilds it
//    whenever the polydata's modification time moves (its IBO cache key kept the polydata's time
//    from an earlier stage; fixed upstream in VTK 9.7, "vtkOpenGLPolyDataMapper: reset TempState
//    before building the IBO cache key"), so every drag step of a 1M-vertex mesh rebuilt and
//    uploaded 2M triangles' indices again;
//  - the bounds (VTK's frustum culler asks every actor for them at every render) are those of the
//    points, from the point array's cached range, instead of a pass over every cell
//    (vtkPolyData::GetCellsBounds): a box containing the cells' bounds, which is all the culler and
//    the clipping range need.
// It also counts its builds (what the level of detail's release uploads: level_of_detail_render_test).

#include <vtkOpenGLPolyDataMapper.h>

namespace ffdkit::app {

class SurfaceMapper : public vtkOpenGLPolyDataMapper {
 public:
  static SurfaceMapper* New();
  vtkTypeMacro(SurfaceMapper, vtkOpenGLPolyDataMapper)

  /// Renders that built the buffer objects (uploaded the arrays that changed since the last build).
  int bufferBuilds() const { return bufferBuilds_; }
  /// Renders that built the triangles' index buffer again (its cache key changed).
  int indexBuilds() const { return indexBuilds_; }

 protected:
  SurfaceMapper() = default;
  ~SurfaceMapper() override = default;
  void BuildBufferObjects(vtkRenderer* renderer, vtkActor* actor) override;
  void BuildIBO(vtkRenderer* renderer, vtkActor* actor, vtkPolyData* poly) override;
  void ComputeBounds() override;

 private:
  SurfaceMapper(const SurfaceMapper&) = delete;
  void operator=(const SurfaceMapper&) = delete;
  int bufferBuilds_ = 0, indexBuilds_ = 0;
};

}  // namespace ffdkit::app
