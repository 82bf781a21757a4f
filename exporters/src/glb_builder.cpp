#include "glb_builder.h"

#include <cstring>
#include <stdexcept>

namespace ffdkit::exporters::detail {

GlbBuilder::GlbBuilder() {
  model_.asset.version = "2.0";
  model_.asset.generator = "ffdkit";
  model_.buffers.emplace_back();
}

int GlbBuilder::addView(const void* data, std::size_t bytes, int target) {
  std::vector<unsigned char>& buffer = model_.buffers[0].data;
  buffer.resize((buffer.size() + 3) / 4 * 4, 0);  // accessors of 4-byte components start aligned
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.size();
  view.byteLength = bytes;
  view.target = target;
  const std::size_t at = buffer.size();
  buffer.resize(at + bytes);
  if (bytes > 0) std::memcpy(buffer.data() + at, data, bytes);
  model_.bufferViews.push_back(view);
  return static_cast<int>(model_.bufferViews.size()) - 1;
}

int GlbBuilder::floatAccessor(const RowMatrixXf& rows, int type, bool bounds, int target) {
  tinygltf::Accessor accessor;
  accessor.bufferView = addView(rows.data(), static_cast<std::size_t>(rows.size()) * sizeof(float), target);
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  accessor.count = static_cast<std::size_t>(rows.rows());
  accessor.type = type;
  if (bounds && rows.rows() > 0) {
    for (Eigen::Index c = 0; c < rows.cols(); ++c) {
      accessor.minValues.push_back(rows.col(c).minCoeff());
      accessor.maxValues.push_back(rows.col(c).maxCoeff());
    }
  }
  model_.accessors.push_back(accessor);
  return static_cast<int>(model_.accessors.size()) - 1;
}

int GlbBuilder::indexAccessor(const Eigen::MatrixXi& rows) {
  std::vector<std::uint32_t> flat;
  flat.reserve(static_cast<std::size_t>(rows.size()));
  for (Eigen::Index r = 0; r < rows.rows(); ++r)
    for (Eigen::Index c = 0; c < rows.cols(); ++c) flat.push_back(static_cast<std::uint32_t>(rows(r, c)));
  tinygltf::Accessor accessor;
  accessor.bufferView = addView(flat.data(), flat.size() * sizeof(std::uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  accessor.count = flat.size();
  accessor.type = TINYGLTF_TYPE_SCALAR;
  model_.accessors.push_back(accessor);
  return static_cast<int>(model_.accessors.size()) - 1;
}

int GlbBuilder::jointAccessor(const Eigen::Matrix<std::uint16_t, Eigen::Dynamic, 4, Eigen::RowMajor>& rows) {
  tinygltf::Accessor accessor;
  accessor.bufferView = addView(rows.data(), static_cast<std::size_t>(rows.size()) * sizeof(std::uint16_t),
                                TINYGLTF_TARGET_ARRAY_BUFFER);
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  accessor.count = static_cast<std::size_t>(rows.rows());
  accessor.type = TINYGLTF_TYPE_VEC4;
  model_.accessors.push_back(accessor);
  return static_cast<int>(model_.accessors.size()) - 1;
}

int GlbBuilder::addNode(tinygltf::Node node) {
  model_.nodes.push_back(std::move(node));
  return static_cast<int>(model_.nodes.size()) - 1;
}

void GlbBuilder::write(std::ostream& out) {
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model_, out, /*prettyPrint=*/false, /*writeBinary=*/true))
    throw std::runtime_error("glTF: tinygltf could not write the model");
}

}  // namespace ffdkit::exporters::detail
