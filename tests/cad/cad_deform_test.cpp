#include "ffdkit/cad/cad_deform.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "cad_test_support.h"
#include "ffdkit/cad/cad_check.h"
#include "ffdkit/cad/cad_error.h"
#include "ffdkit/cad/cad_io.h"
#include "ffdkit/cad/sample_parts.h"
#include "ffdkit/cad/tessellation.h"

namespace ffdkit::cad {
namespace {

using test::deformedLatticeAround;
using test::ffdOf;
using test::ScratchFolder;

/// Lattice control points per axis for each sample: the composed degree (L+M+N) x (surface degree)
/// stays within the default limit of 15.
Eigen::Vector3i countsFor(SamplePart sample) {
  switch (sample) {
    case SamplePart::Blade: return {2, 2, 3};      // cubic loft: 4 x 3 = 12
    case SamplePart::BentPipe: return {2, 3, 2};   // 4 x degree
    default: return {3, 3, 2};                     // 5 x (1, 2 or 3)
  }
}

class ExactDeformation : public ::testing::TestWithParam<SamplePart> {};

TEST_P(ExactDeformation, WritesTheFfdOfTheSurfacesAsAValidWatertightSolid) {
  const CadModel model = makeSamplePart(GetParam());
  const double size = model.bounds().diagonal().norm();
  const ffd::Lattice lattice = deformedLatticeAround(model.bounds(), countsFor(GetParam()), 0.08);
  CadDeformOptions options;
  options.samples = 9;
  const CadDeformResult result = deformCad(model, lattice, options);

  // The written surfaces are the FFD of the original ones (measured at 81 parameters per face against
  // Lattice::evaluate), and every edge lies on both its faces.
  EXPECT_LE(result.report.maxDeviation, 1e-9 * size);
  const CadCheck check = checkModel(result.model);
  EXPECT_TRUE(check.valid) << check.firstProblem;
  EXPECT_LE(result.report.maxGap, check.maxTolerance);
  EXPECT_GT(result.report.maxDegree, 1);
  EXPECT_LE(result.report.maxDegree, options.maxDegree);
  EXPECT_EQ(result.report.approximatedFaces, 0);
  EXPECT_EQ(result.report.approximatedEdges, 0);

  // Same topology: every face, edge and vertex went through the same map.
  EXPECT_EQ(result.model.counts().faces, model.counts().faces);
  EXPECT_EQ(result.model.counts().edges, model.counts().edges);
  EXPECT_EQ(result.model.counts().vertices, model.counts().vertices);
  EXPECT_EQ(result.model.counts().solids, model.counts().solids);

  // Its volume is the volume of the deformed tessellation of the original, within the
  // tessellation's error, and differs from the original volume by far more than that. The
  // tessellation (deflection 3e-5 x size) is refined to triangles shorter than h before the map
  // (planar faces have large triangles that the map bends); the error left is estimated from
  // h = 2% and 1% of the size (chord error ~ h^2: e(h/2) ~ |V(h) - V(h/2)| / 3).
  const auto [finer, tessellationError, area] = test::deformedTessellationVolume(
      model, [&](const Eigen::MatrixX3d& points) { return test::ffdOfRows(lattice, points); });
  EXPECT_NEAR(check.volume, finer, 3.0 * tessellationError);
  EXPECT_GT(std::abs(check.volume - checkModel(model).volume), 10.0 * tessellationError);

  // It re-reads from the written STEP file.
  ScratchFolder folder;
  writeStep(result.model, folder / "deformed.step");
  const CadModel back = readStep(folder / "deformed.step");
  EXPECT_EQ(back.partCount(), model.partCount());
  EXPECT_EQ(back.partName(0), model.partName(0));
  EXPECT_EQ(back.counts().faces, model.counts().faces);
  EXPECT_NEAR(checkModel(back).volume, check.volume, 1e-7 * std::abs(check.volume));
}

INSTANTIATE_TEST_SUITE_P(SampleParts, ExactDeformation, ::testing::ValuesIn(allSampleParts()),
                         [](const auto& part) {
                           std::string name = samplePartName(part.param);
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

CadDeformResult deformBy(CadMethod method, const CadModel& model, const ffd::Lattice& lattice) {
  CadDeformOptions options;
  options.samples = 9;
  options.method = method;
  return deformCad(model, lattice, options);
}

TEST(CadDeform, PoleMovingIsNotTheFfd) {
  const CadModel model = makeSamplePart(SamplePart::FilletedBox);
  const double size = model.bounds().diagonal().norm();
  const ffd::Lattice lattice = deformedLatticeAround(model.bounds(), {3, 3, 2}, 0.08);
  const CadDeformResult poles = deformBy(CadMethod::Poles, model, lattice);
  EXPECT_GT(poles.report.maxDeviation, 1e-3 * size);
  EXPECT_LE(deformBy(CadMethod::Exact, model, lattice).report.maxDeviation, 1e-9 * size);
  EXPECT_LE(poles.report.maxDegree, 3);  // the pole method keeps the degrees
}

TEST(CadDeform, PoleMovingOpensGapsAtTrimmedEdges) {
  // The bottle's faces are trimmed: an edge inside a face's surface moves by its own poles, the
  // surface by its, and they part. Exact composition keeps every edge on its faces.
  const CadModel model = makeSamplePart(SamplePart::Bottle);
  const double size = model.bounds().diagonal().norm();
  const ffd::Lattice lattice = deformedLatticeAround(model.bounds(), {3, 3, 2}, 0.08);
  EXPECT_GT(deformBy(CadMethod::Poles, model, lattice).report.maxGap, 1e-3 * size);
  EXPECT_LE(deformBy(CadMethod::Exact, model, lattice).report.maxGap, 1e-9 * size);
}

TEST(CadDeform, RestLatticeKeepsTheModel) {
  const CadModel model = makeSamplePart(SamplePart::Bottle);
  const double size = model.bounds().diagonal().norm();
  const ffd::Lattice lattice = deformedLatticeAround(model.bounds(), {3, 2, 2}, 0.0);
  CadDeformOptions options;
  options.samples = 5;
  const CadDeformResult result = deformCad(model, lattice, options);
  EXPECT_LE(result.report.maxDeviation, 1e-10 * size);
  const double volume = checkModel(model).volume;
  EXPECT_NEAR(checkModel(result.model).volume, volume, 1e-8 * volume);
}

TEST(CadDeform, PartOutsideTheLatticeIsRefusedWithTheIdentityPolicyWhenExactOnly) {
  const CadModel model = makeSamplePart(SamplePart::FilletedBox);
  Eigen::AlignedBox3d half = model.bounds();
  half.max().x() = half.center().x();
  const ffd::Lattice lattice = deformedLatticeAround(half, {2, 2, 2}, 0.05);
  CadDeformOptions exactOnly;
  exactOnly.approximate = false;
  try {
    deformCad(model, lattice, exactOnly);
    FAIL() << "a part outside the lattice was deformed";
  } catch (const CadError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("filleted-box"), std::string::npos) << message;
    EXPECT_NE(message.find("outside the lattice"), std::string::npos) << message;
  }
}

TEST(CadDeform, ExtrapolatePolicyDeformsAPartBeyondTheLattice) {
  const CadModel model = makeSamplePart(SamplePart::FilletedBox);
  Eigen::AlignedBox3d half = model.bounds();
  half.max().x() = half.center().x();
  ffd::Lattice lattice = deformedLatticeAround(half, {2, 2, 2}, 0.05);
  lattice.setOutsidePolicy(ffd::OutsidePolicy::extrapolate());
  CadDeformOptions options;
  options.samples = 5;
  const CadDeformResult result = deformCad(model, lattice, options);
  EXPECT_LE(result.report.maxDeviation, 1e-9 * model.bounds().diagonal().norm());
  EXPECT_TRUE(checkModel(result.model).valid);
}

TEST(CadDeform, DegreeAboveTheLimitIsRefusedWhenExactOnly) {
  const CadModel model = makeSamplePart(SamplePart::Blade);
  const ffd::Lattice lattice = deformedLatticeAround(model.bounds(), {4, 4, 4}, 0.05);
  CadDeformOptions exactOnly;
  exactOnly.approximate = false;
  try {
    deformCad(model, lattice, exactOnly);
    FAIL() << "degree 27 was accepted";
  } catch (const CadError& error) {
    EXPECT_NE(std::string(error.what()).find("degree 27"), std::string::npos) << error.what();
  }
}

TEST(CadDeform, AssemblyPartsKeepTheirNamesAndPlacements) {
  // The post is placed by a translation: its surfaces must be deformed where the placement puts them
  // (the deviation is measured against the FFD of the placed original).
  const CadModel model = makeSamplePart(SamplePart::TwoPartAssembly);
  const ffd::Lattice lattice = deformedLatticeAround(model.bounds(), {2, 2, 3}, 0.1);
  CadDeformOptions options;
  options.samples = 7;
  const CadDeformResult result = deformCad(model, lattice, options);
  ASSERT_EQ(result.model.partCount(), 2);
  EXPECT_EQ(result.model.partName(0), "plate");
  EXPECT_EQ(result.model.partName(1), "post");
  EXPECT_LE(result.report.maxDeviation, 1e-9 * model.bounds().diagonal().norm());
  EXPECT_TRUE(checkModel(result.model).valid);
}

}  // namespace
}  // namespace ffdkit::cad
