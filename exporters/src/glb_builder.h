#pragma once
// Builds a binary glTF 2.0 model through tinygltf (private to the exporters module): one
// buffer, one buffer view per accessor (4-byte aligned), POSITION accessors with min / max.

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <tiny_gltf.h>

namespace ffdkit::exporters::detail {

using RowMatrixXf = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

class GlbBuilder {
 public:
  GlbBuilder();

  /// float32 accessor of `type` (TINYGLTF_TYPE_SCALAR / VEC3 / VEC4 / MAT4), one row per element;
  /// `bounds`: write min / max (required for POSITION and animation inputs).
  int floatAccessor(const RowMatrixXf& rows, int type, bool bounds, int target = 0);
  /// Unsigned 32-bit element indices (triangles / segments), flattened row by row.
  int indexAccessor(const Eigen::MatrixXi& rows);
  /// Unsigned 16-bit joint indices, VEC4.
  int jointAccessor(const Eigen::Matrix<std::uint16_t, Eigen::Dynamic, 4, Eigen::RowMajor>& rows);

  int addNode(tinygltf::Node node);
  tinygltf::Model& model() { return model_; }

  /// Writes the .glb. @throws std::runtime_error when tinygltf fails.
  void write(std::ostream& out);

 private:
  int addView(const void* data, std::size_t bytes, int target);
  tinygltf::Model model_;
};

}  // namespace ffdkit::exporters::detail
