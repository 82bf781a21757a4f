#include "ffdkit/scenes/up_axis.h"

namespace ffdkit::scenes {

std::string_view upAxisName(UpAxis axis) { return axis == UpAxis::Y ? "y" : "z"; }

Eigen::Matrix3d upAxisRotation(UpAxis axis) {
  if (axis == UpAxis::Z) return Eigen::Matrix3d::Identity();
  Eigen::Matrix3d r;
  r << 1, 0, 0,  //
      0, 0, -1,  //
      0, 1, 0;
  return r;
}

void convertToZUp(MeshData& mesh, UpAxis axis) {
  if (axis == UpAxis::Z) return;
  mesh.points = (mesh.points * upAxisRotation(axis).transpose()).eval();
}

}  // namespace ffdkit::scenes
