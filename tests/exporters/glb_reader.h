#pragma once
// Test support: reads a .glb back with tinygltf and checks its structure independently of the
// writer (buffer views in range, POSITION min / max, weights summing to 1).

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>

#include <Eigen/Core>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

namespace ffdkit::exporters::test {

inline tinygltf::Model readGlb(const std::filesystem::path& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  const bool ok = loader.LoadBinaryFromFile(&model, &err, &warn, path.string());
  EXPECT_TRUE(ok) << path << ": " << err;
  EXPECT_TRUE(warn.empty()) << warn;
  return model;
}

/// An accessor's elements as doubles, one element per row (float32 or unsigned integer data).
inline Eigen::MatrixXd accessorRows(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& a = model.accessors.at(std::size_t(index));
  const tinygltf::BufferView& view = model.bufferViews.at(std::size_t(a.bufferView));
  const tinygltf::Buffer& buffer = model.buffers.at(std::size_t(view.buffer));
  const int columns = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
  const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
  const std::size_t stride = view.byteStride ? view.byteStride : std::size_t(columns * size);
  Eigen::MatrixXd rows(static_cast<Eigen::Index>(a.count), columns);
  const unsigned char* base = buffer.data.data() + view.byteOffset + a.byteOffset;
  for (std::size_t r = 0; r < a.count; ++r) {
    for (int c = 0; c < columns; ++c) {
      const unsigned char* p = base + r * stride + std::size_t(c * size);
      double value = 0.0;
      switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); value = f; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { std::uint32_t i; std::memcpy(&i, p, 4); value = i; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { std::uint16_t i; std::memcpy(&i, p, 2); value = i; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: value = *p; break;
        default: ADD_FAILURE() << "unexpected component type " << a.componentType;
      }
      rows(static_cast<Eigen::Index>(r), c) = value;
    }
  }
  return rows;
}

/// Structure checks every export must pass: each accessor's bytes inside its view, each view
/// inside its buffer, 4-byte alignment, POSITION with min / max equal to its data's bounds,
/// WEIGHTS_n summing to 1 per vertex, JOINTS_n naming joints of the skin.
inline void expectValidStructure(const tinygltf::Model& model) {
  ASSERT_EQ(model.buffers.size(), 1u);
  for (const auto& view : model.bufferViews) {
    EXPECT_LE(view.byteOffset + view.byteLength, model.buffers[0].data.size());
  }
  for (const auto& a : model.accessors) {
    const auto& view = model.bufferViews.at(std::size_t(a.bufferView));
    const std::size_t element = std::size_t(tinygltf::GetNumComponentsInType(std::uint32_t(a.type)) *
                                            tinygltf::GetComponentSizeInBytes(std::uint32_t(a.componentType)));
    EXPECT_LE(a.byteOffset + a.count * element, view.byteLength);
    EXPECT_EQ((view.byteOffset + a.byteOffset) % 4, 0u);
  }
  for (const auto& node : model.nodes) {
    if (node.mesh < 0) continue;
    for (const auto& primitive : model.meshes.at(std::size_t(node.mesh)).primitives) {
      std::vector<std::map<std::string, int>> positionSets{primitive.attributes};
      for (const auto& target : primitive.targets) positionSets.push_back(target);
      for (const auto& attributes : positionSets) {
        const int position = attributes.at("POSITION");
        const auto& a = model.accessors.at(std::size_t(position));
        ASSERT_EQ(a.minValues.size(), 3u);
        ASSERT_EQ(a.maxValues.size(), 3u);
        const Eigen::MatrixXd p = accessorRows(model, position);
        for (int c = 0; c < 3; ++c) {
          EXPECT_EQ(a.minValues[std::size_t(c)], p.col(c).minCoeff());
          EXPECT_EQ(a.maxValues[std::size_t(c)], p.col(c).maxCoeff());
        }
      }
      if (!primitive.attributes.count("WEIGHTS_0")) continue;
      ASSERT_GE(node.skin, 0);
      const std::size_t joints = model.skins.at(std::size_t(node.skin)).joints.size();
      Eigen::VectorXd sum = Eigen::VectorXd::Zero(model.accessors.at(std::size_t(primitive.attributes.at("POSITION"))).count);
      for (int set = 0; primitive.attributes.count("WEIGHTS_" + std::to_string(set)); ++set) {
        const Eigen::MatrixXd w = accessorRows(model, primitive.attributes.at("WEIGHTS_" + std::to_string(set)));
        const Eigen::MatrixXd j = accessorRows(model, primitive.attributes.at("JOINTS_" + std::to_string(set)));
        EXPECT_GE(w.minCoeff(), 0.0);
        EXPECT_LT(j.maxCoeff(), double(joints));
        sum += w.rowwise().sum();
      }
      // glTF: "the linear sum of all weights SHOULD be 1" (validators allow 2e-7 per weight, float32).
      EXPECT_LT((sum.array() - 1.0).abs().maxCoeff(), 1e-6);
    }
  }
}

}  // namespace ffdkit::exporters::test
