#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "ffdkit/geometry/tessellation.h"
#include "ffdkit/scenes/primitive.h"

namespace ffdkit::scenes {

/// How an object looks in the 3D view.
struct DisplaySettings {
  Eigen::Vector3d color{0.85, 0.55, 0.30};  ///< RGB in [0, 1]
  double opacity = 1.0;                     ///< in [0, 1]
  bool visible = true;
};

/// A deformable object: where its points come from and how it is shown.
struct SceneObject {
  std::string name;                     ///< unique within the scene
  std::optional<PrimitiveOptions> primitive;
  DisplaySettings display;
  geometry::TriangleMesh mesh;          ///< the object's own (undeformed) points, built on load
};

/// A box lattice fitted to the bounding box of the objects it deforms (provisional: the
/// widget tree of the widget model replaces it).
struct SceneLattice {
  std::string name;
  std::vector<std::string> objects;     ///< names of the objects it deforms
  Eigen::Vector3i counts{3, 3, 3};      ///< control points per axis, each >= 2
  double padding = 0.05;                ///< added around the bounding box, relative to its diagonal
};

/// The view's camera, in world coordinates.
struct Camera {
  Eigen::Vector3d position{2.4, -3.0, 2.0};
  Eigen::Vector3d focalPoint{0.0, 0.0, 0.0};
  Eigen::Vector3d viewUp{0.0, 0.0, 1.0};
  double viewAngleDegrees = 30.0;
};

/// A document: objects, the lattices that deform them, a camera.
struct Scene {
  std::string description;
  std::vector<SceneObject> objects;
  std::vector<SceneLattice> lattices;
  Camera camera;
  Eigen::Vector3d background{0.13, 0.15, 0.18};  ///< RGB in [0, 1]

  /// The object with this name, or nullptr.
  const SceneObject* findObject(const std::string& name) const;
};

/// The rest box of a lattice: the bounding box of its objects' points, grown by
/// `padding` times the box diagonal on every side (a flat object still gets a solid box).
/// @throws std::invalid_argument if the lattice names an unknown object or has no points.
Eigen::AlignedBox3d latticeRestBox(const Scene& scene, const SceneLattice& lattice);

/// Rest control points of a lattice on the regular grid of its rest box:
/// #points x 3, flat index i + l*(j + m*k).
Eigen::MatrixX3d latticeRestPoints(const Scene& scene, const SceneLattice& lattice);

}  // namespace ffdkit::scenes
