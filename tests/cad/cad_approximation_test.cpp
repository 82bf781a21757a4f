// deformCad beyond one Bernstein polynomial: B-spline lattices composed cell by cell, and the
// approximation (a degree above the limit, knot planes crossed across a face's parameter lines, the
// ClampEdge and Falloff policies, cylindrical lattices), each checked against the FFD of the original.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "cad_test_support.h"
#include "ffdkit/cad/cad_check.h"
#include "ffdkit/cad/cad_deform.h"
#include "ffdkit/cad/cad_error.h"
#include "ffdkit/cad/cad_io.h"
#include "ffdkit/cad/sample_parts.h"
#include "ffdkit/ffd/cylindrical_lattice.h"

namespace ffdkit::cad {
namespace {

using test::cylinderAround;
using test::deformedLatticeAround;
using test::ScratchFolder;

/// What every deformation must be, exact or approximated: the report's deviation from the FFD of
/// the original (measured on a 9 x 9 grid per face, other parameters than the fit's) within
/// `allowed`, BRepCheck valid, every edge on its faces within the model's tolerances, the same
/// topology, the volume of the deformed tessellation of the original (points through the engine's
/// FFD, the outside policy included), and the written STEP re-read with the same volume.
void expectFaithful(const CadModel& model, const ffd::Lattice& lattice, const CadDeformResult& result, double allowed) {
  EXPECT_LE(result.report.maxDeviation, allowed);
  const CadCheck check = checkModel(result.model);
  EXPECT_TRUE(check.valid) << check.firstProblem;
  EXPECT_LE(result.report.maxGap, check.maxTolerance);
  EXPECT_EQ(result.model.counts().faces, model.counts().faces);
  EXPECT_EQ(result.model.counts().edges, model.counts().edges);
  EXPECT_EQ(result.model.counts().vertices, model.counts().vertices);
  EXPECT_EQ(result.model.counts().solids, model.counts().solids);
  const auto [volume, error, area] = test::deformedTessellationVolume(
      model, [&](const Eigen::MatrixX3d& points) { return test::engineFfd(lattice, points); });
  // The surfaces may be off the FFD by `allowed`: that moves the volume by at most allowed x area.
  EXPECT_NEAR(check.volume, volume, 3.0 * error + allowed * area);
  ScratchFolder folder;
  writeStep(result.model, folder / "deformed.step");
  const CadModel back = readStep(folder / "deformed.step");
  EXPECT_EQ(back.counts().faces, model.counts().faces);
  // STEP carries the edges' 3D curves; the reader projects them onto the faces again, which moves
  // the trim of an approximated face by up to its deviation.
  EXPECT_NEAR(checkModel(back).volume, check.volume, 1e-7 * std::abs(check.volume) + allowed * area);
}

CadDeformResult deform(const CadModel& model, const ffd::Lattice& lattice, CadDeformOptions options = {}) {
  options.samples = 9;
  return deformCad(model, lattice, options);
}

bool mentions(const CadDeformReport& report, const std::string& text) {
  for (const std::string& line : report.approximations)
    if (line.find(text) != std::string::npos) return true;
  return false;
}

TEST(CadBSplineLattice, AxisAlignedFacesAreComposedExactlyCellByCell) {
  // A quadratic B-spline lattice of 4 x 4 x 3 points has knot planes through the middle of the box:
  // they cross its planes and its fillets' cylinders along their parameter lines, so every face is
  // split there and composed exactly with each cell's polynomial (degree 6 x the face's).
  const CadModel model = makeSamplePart(SamplePart::FilletedBox);
  const double size = model.bounds().diagonal().norm();
  const ffd::Lattice lattice = deformedLatticeAround(model.bounds(), {4, 4, 3}, 0.08, ffd::AxisBasis::bspline(2));
  const CadDeformResult result = deform(model, lattice);
  EXPECT_EQ(result.report.approximatedFaces, 0) << (result.report.approximations.empty() ? "" : result.report.approximations[0]);
  EXPECT_EQ(result.report.approximatedEdges, 0);
  EXPECT_EQ(result.report.maxDegree, 12);  // the fillets' rational quadratics
  expectFaithful(model, lattice, result, 1e-9 * size);
}

TEST(CadBSplineLattice, CubicLatticeWithUnevenKnots) {
  // Cubic axes (degree sum 9) with a knot plane at 0.3: the plate's planes compose exactly to degree
  // 9; the post's cylinder would reach 18, above the limit, and is approximated.
  Eigen::VectorXd knots(9);
  knots << 0, 0, 0, 0, 0.3, 1, 1, 1, 1;
  const CadModel model = makeSamplePart(SamplePart::TwoPartAssembly);
  const double size = model.bounds().diagonal().norm();
  ffd::Lattice lattice = deformedLatticeAround(model.bounds(), {5, 5, 5}, 0.06, ffd::AxisBasis::bsplineWithKnots(3, knots));
  const CadDeformResult result = deform(model, lattice);
  EXPECT_GT(result.report.approximatedFaces, 0);
  EXPECT_LE(result.report.approximatedFaces, 3);  // the post's side and its two caps at most
  for (const std::string& line : result.report.approximations)
    EXPECT_NE(line.find("part 'post'"), std::string::npos) << line;
  EXPECT_TRUE(mentions(result.report, "degree 18, above the limit of 15"));
  expectFaithful(model, lattice, result, 1e-6 * size);
}

class BSplineLatticeParts : public ::testing::TestWithParam<SamplePart> {};

TEST_P(BSplineLatticeParts, EveryPartFollowsTheFfdWithinTheTolerance) {
  // Faces whose crossing with a knot plane is not a parameter line (the blade, the bottle's sides)
  // and compositions above degree 15 are approximated; the rest is exact.
  const CadModel model = makeSamplePart(GetParam());
  const double size = model.bounds().diagonal().norm();
  const ffd::Lattice lattice = deformedLatticeAround(model.bounds(), {4, 4, 4}, 0.08, ffd::AxisBasis::bspline(2));
  const CadDeformResult result = deform(model, lattice);
  EXPECT_LE(result.report.maxDegree, 15);
  EXPECT_EQ(result.report.tolerance, result.report.approximations.empty() ? 0.0 : 1e-6 * size);
  EXPECT_LE(result.report.approximationError, 1e-6 * size);
  expectFaithful(model, lattice, result, 1e-6 * size);
}

INSTANTIATE_TEST_SUITE_P(SampleParts, BSplineLatticeParts,
                         ::testing::Values(SamplePart::FilletedBox, SamplePart::Blade, SamplePart::BentPipe,
                                           SamplePart::Bottle, SamplePart::TwoPartAssembly),
                         [](const auto& part) {
                           std::string name = samplePartName(part.param);
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

TEST(CadApproximation, DegreeAboveTheLimitIsApproximatedWithinTheTolerance) {
  // 4 x 4 x 4 Bernstein points (degree 9) on the cubic loft: degree 27, above OpenCASCADE's 25.
  const CadModel model = makeSamplePart(SamplePart::Blade);
  const double size = model.bounds().diagonal().norm();
  const ffd::Lattice lattice = deformedLatticeAround(model.bounds(), {4, 4, 4}, 0.05);
  CadDeformOptions options;
  options.tolerance = 1e-5 * size;
  const CadDeformResult result = deform(model, lattice, options);
  EXPECT_EQ(result.report.approximatedFaces, 1);  // the loft; its planar caps compose to degree 9
  EXPECT_TRUE(mentions(result.report, "the exact composition has degree 27, above the limit of 15"));
  EXPECT_LE(result.report.maxDegree, 15);
  EXPECT_EQ(result.report.tolerance, options.tolerance);
  EXPECT_GT(result.report.approximationError, 0.0);
  EXPECT_LE(result.report.approximationError, options.tolerance);
  expectFaithful(model, lattice, result, options.tolerance);

  // A tighter tolerance is met too, with a smaller deviation.
  options.tolerance = 1e-9 * size;
  const CadDeformResult tighter = deform(model, lattice, options);
  EXPECT_LE(tighter.report.maxDeviation, options.tolerance);
  EXPECT_LT(tighter.report.maxDeviation, result.report.maxDeviation);
}

TEST(CadApproximation, AToleranceBeyondReachIsACadError) {
  const CadModel model = makeSamplePart(SamplePart::Blade);
  const ffd::Lattice lattice = deformedLatticeAround(model.bounds(), {4, 4, 4}, 0.05);
  CadDeformOptions options;
  options.tolerance = 1e-15;
  try {
    deformCad(model, lattice, options);
    FAIL() << "a tolerance of 1e-15 was reached";
  } catch (const CadError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("part 'blade', "), std::string::npos) << message;
    EXPECT_NE(message.find("above the tolerance"), std::string::npos) << message;
  }
  options.tolerance = -1.0;
  EXPECT_THROW(deformCad(model, lattice, options), CadError);
}

/// The filleted box with a lattice around its lower-x half only.
ffd::Lattice halfLattice(const CadModel& model, const ffd::OutsidePolicy& policy) {
  Eigen::AlignedBox3d half = model.bounds();
  half.max().x() = half.center().x();
  ffd::Lattice lattice = deformedLatticeAround(half, {3, 3, 2}, 0.04);
  lattice.setOutsidePolicy(policy);
  return lattice;
}

TEST(CadApproximation, ClampEdgeOutsideTheLatticeIsApproximatedAndSaid) {
  const CadModel model = makeSamplePart(SamplePart::FilletedBox);
  const double size = model.bounds().diagonal().norm();
  const ffd::Lattice lattice = halfLattice(model, ffd::OutsidePolicy::clampEdge());
  const CadDeformResult result = deform(model, lattice);
  EXPECT_GT(result.report.approximatedFaces, 0);
  EXPECT_LT(result.report.approximatedFaces, result.report.faces);  // the faces inside stay exact
  EXPECT_TRUE(mentions(result.report, "ClampEdge outside policy"));
  expectFaithful(model, lattice, result, 1e-6 * size);
}

TEST(CadApproximation, FalloffOutsideTheLatticeIsApproximatedAndSaid) {
  const CadModel model = makeSamplePart(SamplePart::FilletedBox);
  const double size = model.bounds().diagonal().norm();
  const ffd::Lattice lattice = halfLattice(model, ffd::OutsidePolicy::falloff(0.5 * model.bounds().sizes().x()));
  const CadDeformResult result = deform(model, lattice);
  EXPECT_GT(result.report.approximatedFaces, 0);
  EXPECT_TRUE(mentions(result.report, "Falloff outside policy"));
  expectFaithful(model, lattice, result, 1e-6 * size);
}

TEST(CadApproximation, ExactOnlyRefusesClampEdgeOutsideTheLattice) {
  const CadModel model = makeSamplePart(SamplePart::FilletedBox);
  CadDeformOptions options;
  options.approximate = false;
  try {
    deformCad(model, halfLattice(model, ffd::OutsidePolicy::clampEdge()), options);
    FAIL() << "ClampEdge outside the lattice was deformed exactly";
  } catch (const CadError& error) {
    EXPECT_NE(std::string(error.what()).find("ClampEdge"), std::string::npos) << error.what();
  }
}

TEST(CadApproximation, CylindricalLatticeIsApproximatedWithinTheUsersTolerance) {
  // Every face and edge is fitted (the FFD is no polynomial), with spans halved where the sampled
  // error exceeds the tolerance: the default 1e-6 x size and a hundred times tighter are both met,
  // the tighter one with a smaller deviation, and the solid is valid.
  const CadModel model = makeSamplePart(SamplePart::Bottle);
  const double size = model.bounds().diagonal().norm();
  const ffd::Lattice lattice = cylinderAround(model);
  const CadDeformResult result = deform(model, lattice);
  EXPECT_EQ(result.report.approximatedFaces, result.report.faces);
  EXPECT_GT(result.report.approximatedEdges, 0);  // every edge with a 3D curve (not the degenerated ones)
  EXPECT_TRUE(mentions(result.report, "cylindrical lattice"));
  EXPECT_EQ(result.report.tolerance, 1e-6 * size);
  EXPECT_LE(result.report.approximationError, 1e-6 * size);
  expectFaithful(model, lattice, result, 1e-6 * size);

  CadDeformOptions tighter;
  tighter.tolerance = 1e-8 * size;
  const CadDeformResult close = deform(model, lattice, tighter);
  EXPECT_LE(close.report.approximationError, tighter.tolerance);
  EXPECT_LE(close.report.maxDeviation, tighter.tolerance);
  EXPECT_LT(close.report.maxDeviation, result.report.maxDeviation);
  EXPECT_TRUE(checkModel(close.model).valid) << checkModel(close.model).firstProblem;
}

TEST(CadApproximation, CylindricalLatticeBeyondReachIsRefusedWithTheDeviationReached) {
  // A tolerance the fit cannot reach within its refinement budget (spans halved six times, at most
  // 96 per direction) is a CadError naming the face or edge, the deviation reached and the tolerance.
  const CadModel model = makeSamplePart(SamplePart::Bottle);
  CadDeformOptions options;
  options.tolerance = 1e-13;
  try {
    deformCad(model, cylinderAround(model), options);
    FAIL() << "a tolerance of 1e-13 was met";
  } catch (const CadError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("part 'bottle', "), std::string::npos) << message;
    EXPECT_NE(message.find("cylindrical lattice"), std::string::npos) << message;
    EXPECT_NE(message.find("reached a deviation of "), std::string::npos) << message;
    EXPECT_NE(message.find("above the tolerance of 1e-13"), std::string::npos) << message;
  }
}

TEST(CadApproximation, CylindricalLatticeIsRefusedWhenExactOnly) {
  // The rest map of a cylindrical lattice is not affine: its FFD is no polynomial of world
  // coordinates, so nothing can be composed exactly.
  const CadModel model = makeSamplePart(SamplePart::Bottle);
  const ffd::Lattice lattice = cylinderAround(model);
  CadDeformOptions exactOnly;
  exactOnly.approximate = false;
  try {
    deformCad(model, lattice, exactOnly);
    FAIL() << "a cylindrical lattice was composed exactly";
  } catch (const CadError& error) {
    EXPECT_NE(std::string(error.what()).find("cylindrical lattice"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace ffdkit::cad
