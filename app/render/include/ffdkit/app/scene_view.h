#pragma once

#include <memory>

#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"

class vtkRenderer;

namespace ffdkit::app {

/// Draws a scene into a VTK renderer: shaded objects at their deformed points, lattice points
/// and edges. The actors rebuild themselves from the model; they hold no state of their own.
class SceneView {
 public:
  /// Draws into `renderer` (not owned; must outlive the view).
  explicit SceneView(vtkRenderer* renderer);
  ~SceneView();
  SceneView(const SceneView&) = delete;
  SceneView& operator=(const SceneView&) = delete;

  /// Replaces what is drawn with `scene`, its objects at the points `deformed` computed, and
  /// sets background and camera from it.
  void show(const scenes::Scene& scene, const scenes::SceneDeformer& deformed);

  /// Sets the renderer's camera from `camera` (clipping range reset to the scene).
  void applyCamera(const scenes::Camera& camera);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ffdkit::app
