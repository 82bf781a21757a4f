// ffdkit::interaction and ffdkit::parts from an installed package: framing the unit cube in a
// parallel view of aspect 1 centres it and scales the view to the margin times the cube's
// bounding-sphere radius (sqrt(3) / 2); the parts library has its four parts, each a triangle
// mesh of about unit size.
#include <cmath>

#include "../consumer_check.h"
#include "ffdkit/interaction/camera_navigation.h"
#include "ffdkit/parts/parts.h"

using namespace ffdkit;

int main() {
  app::ViewCamera view;
  view.parallel = true;
  app::FrameOptions options;
  options.aspect = 1.0;
  options.margin = 1.05;
  const app::ViewCamera framed = app::frame(view, Eigen::AlignedBox3d(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()), options);
  consumer::check((framed.camera.focalPoint - Eigen::Vector3d::Constant(0.5)).norm() < 1e-12, "the cube is centred");
  consumer::check(std::abs(framed.parallelScale - 1.05 * std::sqrt(3.0) / 2.0) < 1e-12, "the cube fits");

  bool valid = app::partNames().size() == 4;
  for (const auto& name : app::partNames()) {
    const auto mesh = app::partMesh(name);
    valid = valid && mesh && mesh->triangles.rows() > 0 && mesh->triangles.minCoeff() >= 0 &&
            mesh->triangles.maxCoeff() < mesh->vertices.rows();
    if (!mesh) continue;
    const double extent = (mesh->vertices.colwise().maxCoeff() - mesh->vertices.colwise().minCoeff()).maxCoeff();
    valid = valid && extent > 0.5 && extent <= 1.2 + 1e-9;
  }
  consumer::check(valid && !app::partMesh("no such part"), "four parts of unit size; an unknown name has none");
  return consumer::exitCode();
}
