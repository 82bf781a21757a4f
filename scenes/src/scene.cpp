#include "ffdkit/scenes/scene.h"

#include <stdexcept>

namespace ffdkit::scenes {

const SceneObject* Scene::findObject(const std::string& name) const {
  for (const auto& object : objects)
    if (object.name == name) return &object;
  return nullptr;
}

Eigen::AlignedBox3d latticeRestBox(const Scene& scene, const SceneLattice& lattice) {
  Eigen::AlignedBox3d box;
  for (const auto& name : lattice.objects) {
    const SceneObject* object = scene.findObject(name);
    if (object == nullptr) {
      throw std::invalid_argument("lattice '" + lattice.name + "': unknown object '" + name + "'");
    }
    for (Eigen::Index i = 0; i < object->mesh.vertices.rows(); ++i)
      box.extend(Eigen::Vector3d(object->mesh.vertices.row(i)));
  }
  if (box.isEmpty()) throw std::invalid_argument("lattice '" + lattice.name + "': its objects have no points");
  const double margin = std::max(lattice.padding * box.diagonal().norm(), 1e-6);
  box.min().array() -= margin;
  box.max().array() += margin;
  return box;
}

Eigen::MatrixX3d latticeRestPoints(const Scene& scene, const SceneLattice& lattice) {
  const Eigen::AlignedBox3d box = latticeRestBox(scene, lattice);
  const Eigen::Vector3i& n = lattice.counts;
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(n.prod()), 3);
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        const Eigen::Array3d t(double(i) / (n.x() - 1), double(j) / (n.y() - 1), double(k) / (n.z() - 1));
        points.row(i + n.x() * (j + n.y() * k)) = (box.min().array() + t * box.sizes().array()).matrix().transpose();
      }
  return points;
}

}  // namespace ffdkit::scenes
