#include "ffdkit/cad/tessellation.h"

#include <cmath>

#include <gtest/gtest.h>

#include "ffdkit/cad/cad_check.h"
#include "ffdkit/cad/cad_error.h"
#include "ffdkit/cad/sample_parts.h"

namespace ffdkit::cad {
namespace {

double triangleArea(const CadTriangles& mesh) {
  double area = 0.0;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    const Eigen::Vector3d a = mesh.points.row(mesh.triangles(t, 0)), b = mesh.points.row(mesh.triangles(t, 1)),
                          c = mesh.points.row(mesh.triangles(t, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

TEST(Tessellation, EverySamplePartEnclosesItsVolumeWithinTheDeflection) {
  for (SamplePart sample : allSampleParts()) {
    const CadModel model = makeSamplePart(sample);
    TessellationOptions options;
    options.linearDeflection = 0.01;
    const CadTriangles mesh = tessellate(model, options);
    ASSERT_GT(mesh.triangles.rows(), 0) << samplePartName(sample);
    EXPECT_EQ(mesh.partOfTriangle.size(), mesh.triangles.rows());
    const double exact = checkModel(model).volume;
    // Between a surface and its triangles lies at most area x deflection of volume.
    EXPECT_NEAR(enclosedVolume(mesh.points, mesh.triangles), exact, triangleArea(mesh) * options.linearDeflection)
        << samplePartName(sample);
  }
}

TEST(Tessellation, FinerDeflectionGivesMoreTriangles) {
  const CadModel coarse = makeSamplePart(SamplePart::BentPipe);
  const CadModel fine = makeSamplePart(SamplePart::BentPipe);
  TessellationOptions options;
  options.linearDeflection = 0.5;
  const auto few = tessellate(coarse, options).triangles.rows();
  options.linearDeflection = 0.01;
  EXPECT_GT(tessellate(fine, options).triangles.rows(), 4 * few);
}

TEST(Tessellation, RefusesNonPositiveDeflections) {
  const CadModel model = makeSamplePart(SamplePart::FilletedBox);
  TessellationOptions options;
  options.linearDeflection = -1.0;
  EXPECT_THROW(tessellate(model, options), CadError);
  options.linearDeflection = 0.1;
  options.angularDeflection = std::nan("");
  EXPECT_THROW(tessellate(model, options), CadError);
}

TEST(Tessellation, EnclosedVolumeOfAUnitCube) {
  Eigen::MatrixX3d points(8, 3);
  points << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  Eigen::MatrixX3i triangles(12, 3);
  triangles << 0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7;
  EXPECT_NEAR(enclosedVolume(points, triangles), 1.0, 1e-15);
}

}  // namespace
}  // namespace ffdkit::cad
