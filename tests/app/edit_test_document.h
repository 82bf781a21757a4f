// The headless document the edit-mode tests drive (edit_controller_test.cpp, edit_guards_test.cpp):
// a scene with its deformer, undo stack, interaction controller and edit controller, and the
// helpers that address a 3 x 3 x 3 lattice's points and look down at them.
#pragma once

#include <Eigen/Core>

#include "ffdkit/interaction/edit_controller.h"
#include "ffdkit/scenes/scene_deformer.h"

namespace ffdkit::app::test {

/// A scene with everything that edits it, as the app wires them.
struct Document {
  scenes::Scene scene;
  scenes::SceneDeformer deformer;
  scenes::CommandStack commands;
  InteractionController controller{scene, deformer, commands};
  EditController edit{scene, deformer, commands, controller};
};

/// The flat index of point (i, j, k) of a 3 x 3 x 3 lattice.
inline Eigen::Index f(int i, int j, int k) { return i + 3 * (j + 3 * k); }

/// Looking down -z at the point p.
inline widgets::Ray downAt(const Eigen::Vector3d& p) {
  widgets::Ray r;
  r.origin = p + Eigen::Vector3d(0, 0, 10);
  r.direction = {0, 0, -1};
  return r;
}

/// The view direction of downAt.
inline const Eigen::Vector3d kView(0, 0, -1);

}  // namespace ffdkit::app::test
