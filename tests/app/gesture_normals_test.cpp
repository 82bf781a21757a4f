// The view's normal passes (app/render/src/gesture_normals.h) give the bits of their scalar
// arithmetic in every vector form: exactNormals normalises a chunk of gathered sums four or eight
// at a time, and its normals must be, bit for bit, the sums' normalised one by one as written here.
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>

#include "gesture_normals.h"
#include "scene_view_shapes.h"

namespace ffdkit::app {
namespace {

// The scalar normalisation: 1 / sqrt(x^2 + y^2 + z^2) times the sum, +z for a zero sum.
Eigen::Vector3f normalised(float x, float y, float z) {
  const float inverse = 1.0f / std::sqrt(x * x + y * y + z * z);
  if (!(inverse < std::numeric_limits<float>::infinity())) return Eigen::Vector3f(0.0f, 0.0f, 1.0f);
  return Eigen::Vector3f(x * inverse, y * inverse, z * inverse);
}

TEST(GestureNormals, ExactNormalsAreTheScalarNormalisationOfTheirSumsBitForBit) {
  // Random triangles over 3001 random points (not a multiple of four or eight: the last few take
  // the scalar form) on sizes from 1e-3 to 1e3, and points in no triangle (zero sums: +z).
  std::mt19937 rng(39);
  for (const int n : {3001, 20011}) {  // the second on both cores
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    std::uniform_int_distribution<int> pick(0, n - 1 - n / 20);  // the last twentieth in no triangle
    Eigen::MatrixX3d points(n, 3);
    for (Eigen::Index i = 0; i < n; ++i)
      points.row(i) = std::pow(10.0, 3.0 * U(rng)) * Eigen::RowVector3d(U(rng), U(rng), U(rng));
    Eigen::MatrixX3i triangles(2 * n, 3);
    for (Eigen::Index t = 0; t < triangles.rows(); ++t) triangles.row(t) << pick(rng), pick(rng), pick(rng);
    const scene_view_shapes::VertexFaces vf = scene_view_shapes::vertexFaces(triangles, n);
    const Eigen::Vector3d origin(0.25, -0.5, 2.0);
    std::vector<Eigen::Vector3f> scratch;
    Eigen::MatrixX3f sums;
    vtkNew<vtkPoints> drawn;
    vtkNew<vtkFloatArray> normals;
    exactNormals(triangles, vf, points, origin, scratch, sums, drawn, normals);
    ASSERT_EQ(sums.rows(), n);
    ASSERT_EQ(normals->GetNumberOfTuples(), n);
    const float* out = normals->GetPointer(0);
    const float* xyz = static_cast<const float*>(drawn->GetVoidPointer(0));
    int zero = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector3f expected = normalised(sums(i, 0), sums(i, 1), sums(i, 2));
      zero += sums.row(i).isZero(0.0);
      for (int c = 0; c < 3; ++c) {
        ASSERT_EQ(out[3 * i + c], expected[c]) << "vertex " << i << " coordinate " << c;
        ASSERT_EQ(xyz[3 * i + c], static_cast<float>(points(i, c) - origin[c])) << "vertex " << i;
      }
    }
    EXPECT_GE(zero, n / 20);
    // And the sums are the triangles' area vectors summed (in double here): the normals of the mesh.
    Eigen::MatrixX3d reference = Eigen::MatrixX3d::Zero(n, 3);
    for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
      const Eigen::Vector3d a = points.row(triangles(t, 0)), b = points.row(triangles(t, 1)), c = points.row(triangles(t, 2));
      const Eigen::RowVector3d area = (b - a).cross(c - a).transpose();
      for (int k = 0; k < 3; ++k) reference.row(triangles(t, k)) += area;
    }
    for (Eigen::Index i = 0; i < n; ++i) {
      const double size = reference.row(i).norm();
      if (size == 0.0) continue;
      EXPECT_LT((sums.row(i).cast<double>() - reference.row(i)).norm(), 1e-5 * size + 1e-30) << "vertex " << i;
    }
  }
}

}  // namespace
}  // namespace ffdkit::app
