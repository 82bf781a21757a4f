#pragma once

// The level-of-detail proxy of one object as SceneView draws it (private to ffdkit::render;
// LevelOfDetail in scene_view.h): an actor beside the object's own, drawing lod_proxy.h's
// decimation at the deformer's points, and sharing the object actor's property (colour, opacity,
// highlights). SceneView shows one of the two actors at a time.
//
// Points during a gesture: the view asks the deformer for the object at the proxy's vertices only
// (SceneView::evaluationRequest, scenes::EvaluationRequest), so the deformer evaluates those
// points through their own embedding, built once per object, and leaves the full mesh for the
// gesture's end (scenes::PointCoverage::Subset); the proxy draws SceneDeformer::subsetPoints and a
// step costs the proxy's size, never the mesh's. When the object is evaluated in full (playback,
// an exact reader asked during the gesture) the proxy gathers the full points at its vertices.

#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <vtkActor.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include "ffdkit/meshio/mesh_data.h"
#include "ffdkit/render/scene_view.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "lod_proxy.h"

class vtkRenderer;

namespace ffdkit::app {

class ObjectProxy {
 public:
  /// Decimates `mesh` (its own points and triangles: clusterVertices to about `targetVertices`)
  /// and adds its actor, hidden, to `renderer`, sharing `full`'s property.
  ObjectProxy(vtkRenderer* renderer, vtkActor* full, const meshio::MeshData& mesh, Eigen::Index targetVertices);
  /// Removes the proxy's actor from the renderer.
  ~ObjectProxy();
  ObjectProxy(const ObjectProxy&) = delete;
  ObjectProxy& operator=(const ObjectProxy&) = delete;

  /// Draws the proxy (true) or the object's own actor (false), hiding the other.
  void show(bool proxy);
  /// True while the proxy is drawn.
  bool shown() const { return shown_; }
  /// Brings the proxy's points and normals to the deformer's present points of `object`: its
  /// subset points when the deformer evaluated the object at this proxy's vertices, the full
  /// points at them otherwise. Returns false when they already were (the object's revision did
  /// not move), or when the deformer holds another subset of the object (then nothing is drawn).
  bool update(const scenes::SceneDeformer& deformer, scenes::ObjectId object);
  /// The mesh's index of each proxy vertex, increasing: what the view asks the deformer for
  /// during a gesture (EvaluationRequest::subsets).
  const std::vector<Eigen::Index>& vertices() const { return mesh_.vertices; }
  /// The proxy's vertex count.
  Eigen::Index vertexCount() const { return static_cast<Eigen::Index>(mesh_.vertices.size()); }
  /// The target the proxy was built for (a change of LevelOfDetail::proxyVertices builds it anew).
  Eigen::Index targetVertices() const { return target_; }
  /// Heap bytes held: the VTK data, the vertex subset and the gathered points.
  std::size_t memoryBytes() const;

 private:
  void gather(const Eigen::MatrixX3d& points, Eigen::MatrixX3d& out) const;
  void draw(const Eigen::MatrixX3d& points);

  vtkRenderer* renderer_;
  vtkSmartPointer<vtkActor> full_, actor_;
  vtkSmartPointer<vtkPolyData> polyData_;
  ProxyMesh mesh_;
  Eigen::Index target_ = 0;
  bool shown_ = false;
  std::uint64_t drawnRevision_ = 0;
  bool drawn_ = false;
  Eigen::MatrixX3d scratch_;  // the full points gathered at the proxy's vertices
};

/// True when `object`, drawn with `pointCount` points and `display`, has a proxy under `lod`: the
/// level of detail on, at least lod.minVertices points, triangles, not zebra-striped, and its own
/// points as many as drawn.
bool hasProxy(const LevelOfDetail& lod, const scenes::SceneObject* object, Eigen::Index pointCount,
              const scenes::DisplaySettings& display);

/// Brings `proxy` to what `lod` asks of the object drawn by `full`: built (hidden) when the object
/// has a proxy but none of lod.proxyVertices yet, let go when it has none (hasProxy). SceneView
/// calls it when an object's actor is built and at each refresh, so the first gesture or played
/// frame draws the proxy without building it. Returns true when it built one.
bool prepareObjectProxy(std::unique_ptr<ObjectProxy>& proxy, const LevelOfDetail& lod, vtkRenderer* renderer,
                        vtkActor* full, const scenes::SceneObject* object, Eigen::Index pointCount,
                        const scenes::DisplaySettings& display);

}  // namespace ffdkit::app
