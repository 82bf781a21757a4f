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
// And it culls back faces where the geometry hides them (setClosedSurface, cullsBackFaces): half
// the triangles of a closed surface face away from the eye, and a software GL (Mesa's llvmpipe)
// drops them after shading their vertices, before its triangle setup, binning and rasterisation
// (a frame of the full 1M-vertex sphere: about 135 instead of 225 ms of CPU). The image is VTK's
// but for a few pixels where the surface is seen edge-on, which VTK's own image shades with a
// back face that rounding lets through (surface_culling_test: 0 to 3 of 76,800 pixels; it draws
// closed, open and inward-facing surfaces from outside and inside both ways and compares).
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
  /// Renders that drew with back faces culled (cullsBackFaces was true).
  int culledDraws() const { return culledDraws_; }

  /// Declares that the input's triangles bound a solid and face out of it: every edge is shared by
  /// exactly two triangles that run along it in opposite directions, and the enclosed volume is
  /// positive (closedOutwardSurface in closed_surface.h). Computed once per topology by the
  /// caller; false (the default) never culls.
  void setClosedSurface(bool closed) { closedSurface_ = closed; }
  /// What setClosedSurface declared.
  bool closedSurface() const { return closedSurface_; }
  /// Declares whether the points may have been moved by a map that folds space or tears the
  /// surface (SceneView asks OutwardFacesGuard, outward_faces.h, and the fold-over tints): a fold
  /// can turn part of a closed surface inside out through the rest, so that a back face is the
  /// nearest. True by default; false never culls.
  void setFoldFree(bool foldFree) { foldFree_ = foldFree; }
  /// True when the surface is drawn now with its back faces culled: a closed surface
  /// (setClosedSurface) not folded (setFoldFree), opaque, drawn as a surface (not wireframe,
  /// points or edges), without clipping planes or hardware picking, its actor's matrix keeping
  /// orientation, and its whole bounding box beyond the camera's near clipping plane. Then the eye
  /// is outside the solid and nothing of it is clipped away, so every ray from the eye enters the
  /// solid through a front face before it meets a back face: the depth test hides the back faces
  /// anyway, but for rounding where the surface is seen edge-on.
  bool cullsBackFaces(vtkRenderer* renderer, vtkActor* actor);

 protected:
  SurfaceMapper() = default;
  ~SurfaceMapper() override = default;
  void BuildBufferObjects(vtkRenderer* renderer, vtkActor* actor) override;
  void BuildIBO(vtkRenderer* renderer, vtkActor* actor, vtkPolyData* poly) override;
  void ComputeBounds() override;
  void RenderPieceDraw(vtkRenderer* renderer, vtkActor* actor) override;

 private:
  SurfaceMapper(const SurfaceMapper&) = delete;
  void operator=(const SurfaceMapper&) = delete;
  int bufferBuilds_ = 0, indexBuilds_ = 0, culledDraws_ = 0;
  bool closedSurface_ = false, foldFree_ = true;
};

}  // namespace ffdkit::app
