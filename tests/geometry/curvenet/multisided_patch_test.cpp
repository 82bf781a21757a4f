#include "ffdkit/geometry/curvenet/multisided_patch.h"

#include <cmath>
#include <iostream>
#include <numbers>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "continuity_check.h"
#include "ffdkit/geometry/curvenet/example_networks.h"

namespace ffdkit::geometry::curvenet {
namespace {

using testing::sharedEdgeMismatch;

void expectG2(const testing::EdgeMismatch& m, double scale, int pairs) {
  EXPECT_EQ(m.pairs, pairs);
  EXPECT_LE(m.boundary, 1e-12 * scale) << "P1 boundary interpolation";
  EXPECT_LE(m.position, 1e-12 * scale) << "P4 shared boundary";
  EXPECT_LE(m.angle, 1e-9) << "P5 G1";
  EXPECT_LE(m.curvature, 1e-8) << "P6 G2";
}

TEST(MultisidedPatch, SphereOctantsInterpolateAndJoinG2OnAllTwelveEdges) {  // F3, P1, P4-P6
  const CurveNetwork net = buildCurveNetwork(sphereOctantNetwork());
  const auto m = sharedEdgeMismatch(net);
  expectG2(m, net.scale, 12);
  double farthest = 0.0;
  for (int f = 0; f < 8; ++f) {
    const NGonDomain d(3);
    for (double x = -0.4; x <= 0.4; x += 0.1) {
      for (double y = -0.4; y <= 0.4; y += 0.1) {
        farthest = std::max(farthest, std::abs(evaluatePatch(net, f, d, {x, y}).v.norm() - 1.0));
      }
    }
  }
  ::testing::Test::RecordProperty("max_distance_from_unit_sphere", std::to_string(farthest));
  std::cout << "F3 max distance from the unit sphere: " << farthest << "\n";
  EXPECT_LT(farthest, 0.05);
}

TEST(MultisidedPatch, BSplineCurveWithAGapIsCorrectedAndStillJoinsG2) {  // Kuriyama 1996, sec. 5.3.3
  CurveNetworkDescription d = sphereOctantNetwork();
  // A periodic uniform cubic B-spline passes through (P_{k-1} + 4 P_k + P_{k+1}) / 6 at its
  // knots: scale its control circle so it misses the other two curves by 0.003.
  const double radius = 1.003 * 6.0 / (4.0 + 2.0 * std::cos(std::numbers::pi / 4));
  CurveDescription& c = d.curves[0];
  c.kind = CurveDescription::Kind::BSpline;
  c.points *= radius;
  c.knots = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  const CurveNetwork net = buildCurveNetwork(d);
  ASSERT_EQ(net.faces.size(), 8u);
  EXPECT_LE(net.correctionResidual, 1e-9 * net.scale);
  expectG2(sharedEdgeMismatch(net), net.scale, 12);
}

// F6: pentagon (0,0)(2,0)(2,1.5)(1.5,2)(0,2) cut by x + y = 3.5, the triangle beyond the cut
// and the quad [0,2] x [-2,0], lifted onto the prototype height field.
CurveNetworkDescription pentagonNetwork(double influenceOnX2) {
  auto lifted = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, int n) {
    Eigen::MatrixX3d p(n, 3);
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector2d q = a + (b - a) * k / (n - 1.0);
      p.row(k) << q.x(), q.y(), prototypeHeight(q.x(), q.y());
    }
    return p;
  };
  CurveNetworkDescription d;
  auto add = [&](const std::string& name, Eigen::Vector2d a, Eigen::Vector2d b, int n) {
    CurveDescription c;
    c.name = name;
    c.points = lifted(a, b, n);
    d.curves.push_back(c);
  };
  add("y=-2", {-0.3, -2}, {2.3, -2}, 11);
  add("y=0", {-0.3, 0}, {2.3, 0}, 11);
  add("y=2", {-0.3, 2}, {2.3, 2}, 11);
  add("x=0", {0, -2.3}, {0, 2.3}, 15);
  add("x=2", {2, -2.3}, {2, 2.3}, 15);
  add("x+y=3.5", {1.2, 2.3}, {2.3, 1.2}, 7);
  d.curves[4].influence = influenceOnX2;
  return d;
}

TEST(MultisidedPatch, PentagonTriangleAndQuadJoinG2ForAnyInfluenceWeight) {  // F6
  for (double w : {1.0, 3.0}) {
    const CurveNetwork net = buildCurveNetwork(pentagonNetwork(w));
    std::vector<int> sides;
    for (const Face& f : net.faces) sides.push_back(static_cast<int>(f.sides.size()));
    std::sort(sides.begin(), sides.end());
    ASSERT_EQ(sides, (std::vector<int>{3, 4, 5})) << "w = " << w;
    expectG2(sharedEdgeMismatch(net), net.scale, 2);
    PatchOptions m1;
    m1.blendingExponent = 1;
    EXPECT_GT(sharedEdgeMismatch(net, m1).curvature, 1e-2) << "m = 1 negative control, w = " << w;
  }
}

// The other reading of the thesis: each transversal normalised separately,
// C^-(Delta_{i-1} d) and C^+(Delta_{i+1} d), instead of one shared v.
VectorJet separatelyNormalisedPatch(const CurveNetwork& net, int f, const NGonDomain& d, const Eigen::Vector2d& p) {
  const Face& face = net.faces[f];
  const int n = d.sides();
  const auto b = d.barycentric(p);
  const auto blend = d.blend(b, 3);
  auto transversal = [&](const Transversal& tr, const Jet& v) {
    VectorJet sum;
    for (std::size_t k = 0; k < tr.members.size(); ++k) {
      const NetworkCurve& c = net.curves[tr.members[k].curve];
      const Jet t = tr.members[k].parameter + tr.directions[k] * v;
      sum = sum + (1.0 / tr.members.size()) * compose(c.evaluate(t.v), c.evaluate(t.v, 1), c.evaluate(t.v, 2), t);
    }
    sum.v -= net.vertices[tr.vertex].position;
    return sum;
  };
  VectorJet q;
  for (int i = 0; i < n; ++i) {
    const FaceSide& side = face.sides[i];
    const curvenet::Run& run = net.runs[side.run];
    const double dPrev = face.sides[(i - 1 + n) % n].delta, dNext = face.sides[(i + 1) % n].delta;
    const Jet ut = d.uTilde(i, b), dist = d.distance(i, b);
    const Jet utRun = side.forward ? ut : 1.0 - ut;
    const double sign = side.forward ? 1.0 : -1.0;
    const Jet vStart = sign * (side.forward ? dPrev : dNext) * dist;
    const Jet vEnd = sign * (side.forward ? dNext : dPrev) * dist;
    const Jet tGuide = run.tStart + run.delta() * utRun;
    const NetworkCurve& g = net.curves[run.curve];
    const VectorJet guide = compose(g.evaluate(tGuide.v), g.evaluate(tGuide.v, 1), g.evaluate(tGuide.v, 2), tGuide);
    const VectorJet sub = (1.0 - utRun) * transversal(run.atStart, vStart) + utRun * transversal(run.atEnd, vEnd) + guide;
    q = q + blend[i] * sub;
  }
  return q;
}

TEST(MultisidedPatch, SeparatelyNormalisedTransversalsBreakG1) {  // P7, A8 negative control
  const CurveNetwork net = buildCurveNetwork(pentagonNetwork(1.0));
  double worstAngle = 0.0, worstBoundary = 0.0;
  for (int f = 0; f < static_cast<int>(net.faces.size()); ++f) {
    const NGonDomain df(static_cast<int>(net.faces[f].sides.size()));
    for (int i = 0; i < df.sides(); ++i) {
      const FaceSide& a = net.faces[f].sides[i];
      for (int g = f + 1; g < static_cast<int>(net.faces.size()); ++g) {
        const NGonDomain dg(static_cast<int>(net.faces[g].sides.size()));
        for (int j = 0; j < dg.sides(); ++j) {
          const FaceSide& b = net.faces[g].sides[j];
          if (b.run != a.run) continue;
          for (double u : {0.2, 0.5, 0.8}) {
            const double sa = a.forward ? u : 1 - u, sb = b.forward ? u : 1 - u;
            const VectorJet qa = separatelyNormalisedPatch(net, f, df, testing::sidePoint(df, i, sa));
            const VectorJet qb = separatelyNormalisedPatch(net, g, dg, testing::sidePoint(dg, j, sb));
            worstBoundary = std::max(worstBoundary, (qa.v - qb.v).norm());
            const Eigen::Vector3d na = patchNormal(qa), nb = patchNormal(qb);
            worstAngle = std::max(worstAngle, std::atan2(na.cross(nb).norm(), na.dot(nb)));
          }
        }
      }
    }
  }
  EXPECT_LE(worstBoundary, 1e-12 * net.scale) << "still interpolates the shared curves";
  EXPECT_GT(worstAngle, 1e-4) << "but the tangent planes no longer match";
}

// F10: two open curves crossing like a '+', lifted by `lift` (z offset + height field scale).
CurveNetworkDescription crossNetwork(double zOffset, double heightScale) {
  CurveNetworkDescription d;
  auto add = [&](const std::string& name, Eigen::Vector2d a, Eigen::Vector2d b) {
    CurveDescription c;
    c.name = name;
    c.points.resize(9, 3);
    for (int k = 0; k < 9; ++k) {
      const Eigen::Vector2d q = a + (b - a) * k / 8.0;
      c.points.row(k) << q.x(), q.y(), zOffset + heightScale * prototypeHeight(q.x(), q.y());
    }
    d.curves.push_back(c);
  };
  add("y=0", {-1.0, 0.0}, {1.5, 0.0});
  add("x=0", {0.0, -1.0}, {0.0, 1.2});
  return d;
}

TEST(MultisidedPatch, OpenRegionsAreFilledOnRequestWithVirtualSides) {  // F10, rule (c)
  CurveNetworkOptions fill;
  fill.fillOpenRegions = true;
  EXPECT_TRUE(buildCurveNetwork(crossNetwork(0.0, 1.0)).faces.empty()) << "not filled by default";
  const CurveNetwork net = buildCurveNetwork(crossNetwork(0.0, 1.0), fill);
  ASSERT_EQ(net.faces.size(), 4u);
  for (const Face& f : net.faces) {
    EXPECT_TRUE(f.openRegion);
    ASSERT_EQ(f.sides.size(), 3u);
    EXPECT_EQ(f.sides[2].run, -1);
  }
  // The two real sides are interpolated and the quadrants join G2 across the dangling pieces.
  expectG2(sharedEdgeMismatch(net), net.scale, 4);
  // Sum of the modified weights is 1: a planar network off the origin stays in its plane,
  // the virtual edge included.
  const CurveNetwork flat = buildCurveNetwork(crossNetwork(1.0, 0.0), fill);
  ASSERT_EQ(flat.faces.size(), 4u);
  const NGonDomain d(3);
  for (int f = 0; f < 4; ++f) {
    for (double s : {0.1, 0.5, 0.9}) {
      const Eigen::Vector2d onVirtual = (1 - s) * d.vertex(2) + s * d.vertex(0);
      EXPECT_NEAR(evaluatePatch(flat, f, d, onVirtual).v.z(), 1.0, 1e-12);
      EXPECT_NEAR(evaluatePatch(flat, f, d, 0.5 * onVirtual).v.z(), 1.0, 1e-12);
    }
  }
}

// F5: the L-shaped region (0,0)(2,0)(2,1)(1,1)(1,2)(0,2) on the height field; `split` runs
// x = 1 through the whole L, which cuts it into two quads.
CurveNetworkDescription lShapeNetwork(bool split) {
  CurveNetworkDescription d;
  auto add = [&](const std::string& name, Eigen::Vector2d a, Eigen::Vector2d b) {
    CurveDescription c;
    c.name = name;
    c.points.resize(9, 3);
    for (int k = 0; k < 9; ++k) {
      const Eigen::Vector2d q = a + (b - a) * k / 8.0;
      c.points.row(k) << q.x(), q.y(), prototypeHeight(q.x(), q.y());
    }
    d.curves.push_back(c);
  };
  add("y=0", {-0.3, 0}, {2.3, 0});
  add("x=2", {2, -0.3}, {2, 1.3});
  add("y=1", {split ? 1.0 : 0.7, 1}, {2.3, 1});  // split: a T-junction on x = 1
  add("x=1", {1, split ? -0.3 : 0.7}, {1, 2.3});
  add("y=2", {-0.3, 2}, {1.3, 2});
  add("x=0", {0, -0.3}, {0, 2.3});
  return d;
}

TEST(MultisidedPatch, ConcaveRegionIsReportedAndSplittingItGivesUnfoldedQuads) {  // F5
  const CurveNetwork concave = buildCurveNetwork(lShapeNetwork(false));
  EXPECT_TRUE(concave.faces.empty()) << "a reflex corner is never traced (Kuriyama 1996, sec. 5.3.3)";
  EXPECT_FALSE(concave.openChains.empty());
  const CurveNetwork split = buildCurveNetwork(lShapeNetwork(true));
  ASSERT_EQ(split.faces.size(), 2u);
  expectG2(sharedEdgeMismatch(split), split.scale, 1);
  // Fold diagnostic: (Q_x x Q_y) . n_ref keeps its sign over each patch.
  for (int f = 0; f < 2; ++f) {
    const NGonDomain d(4);
    const Eigen::Vector3d ref = patchNormal(evaluatePatch(split, f, d, Eigen::Vector2d::Zero()));
    for (double x = -0.68; x <= 0.68; x += 0.085) {
      for (double y = -0.68; y <= 0.68; y += 0.085) {
        const VectorJet q = evaluatePatch(split, f, d, {x, y});
        EXPECT_GT(q.x.cross(q.y).dot(ref), 0.0);
      }
    }
  }
}

TEST(MultisidedPatch, HeightGridJoinsG2AndExponentOneLosesG2) {  // P6, P7
  const CurveNetwork net = buildCurveNetwork(heightGridNetwork(4));
  expectG2(sharedEdgeMismatch(net), net.scale, 12);
  PatchOptions m1;
  m1.blendingExponent = 1;
  const auto bad = sharedEdgeMismatch(net, m1);
  EXPECT_LE(bad.angle, 1e-9) << "m = 1 is still G1";
  EXPECT_GT(bad.curvature, 1e-2) << "m = 1 must fail G2 (negative control)";
}

TEST(MultisidedPatch, BenchmarkGridOfFiftyCurvesHas576QuadsJoiningG2) {  // bench input
  const CurveNetwork net = buildCurveNetwork(heightGridNetwork(25));
  ASSERT_EQ(net.faces.size(), 576u);
  for (const Face& f : net.faces) EXPECT_EQ(f.sides.size(), 4u);
  expectG2(sharedEdgeMismatch(net), net.scale, 2 * 24 * 23);
}

TEST(MultisidedPatch, MultiplePointsJoinG2AwayFromThePoles) {  // F9, rule (a)
  const CurveNetwork net = buildCurveNetwork(meridianNetwork());
  expectG2(sharedEdgeMismatch(net, {}, 1e-3), net.scale, 18);
  // Normal spread near the poles (vertex enclosure, reported only).
  double spread = 0.0;
  for (int f = 0; f < 12; ++f) {
    const NGonDomain d(3);
    for (int k = 0; k < 3; ++k) {
      const int v = net.faces[f].sides[k].startVertex;
      if (net.vertices[v].kind != NetworkVertex::Kind::Multiple) continue;
      const Eigen::Vector2d p = (1 - 1e-3) * d.vertex(k);
      const Eigen::Vector3d n = patchNormal(evaluatePatch(net, f, d, p));
      spread = std::max(spread, std::acos(std::clamp(n.dot(net.vertices[v].normal), -1.0, 1.0)));
    }
  }
  std::cout << "F9 normal spread at 1e-3 from the poles: " << spread << " rad\n";
  EXPECT_LT(spread, 0.1);
}

TEST(MultisidedPatch, WithoutAveragingAMultiplePointBreaksG1) {  // P7 negative control
  // Without rule (a) the faces on the two sides of a meridian take different single curves
  // as transversal at the pole: model that with one network per side.
  const CurveNetwork net = buildCurveNetwork(meridianNetwork());
  CurveNetwork first = net, second = net;
  for (int r = 0; r < static_cast<int>(net.runs.size()); ++r) {
    for (int end = 0; end < 2; ++end) {
      Transversal& a = end == 0 ? first.runs[r].atStart : first.runs[r].atEnd;
      Transversal& b = end == 0 ? second.runs[r].atStart : second.runs[r].atEnd;
      if (a.members.size() < 2) continue;
      a.members = {a.members[0]};
      a.directions = {a.directions[0]};
      b.members = {b.members[1]};
      b.directions = {b.directions[1]};
    }
  }
  EXPECT_GT(sharedEdgeMismatch(first, {}, 1e-3, &second).angle, 1e-3);
  EXPECT_LE(sharedEdgeMismatch(net, {}, 1e-3).angle, 1e-9);
}

TEST(MultisidedPatch, SpecialRulesNeedExponentThreeForG2) {  // Kuriyama 1996, sec. 5.2.3 (iii), P7
  PatchOptions m2;
  m2.blendingExponent = 2;
  const CurveNetwork tee = buildCurveNetwork(tJunctionNetwork());
  const auto t2 = sharedEdgeMismatch(tee, m2);
  EXPECT_LE(t2.angle, 1e-9) << "G1 with m = 2";
  EXPECT_GT(t2.curvature, 1e-2) << "but not G2";
  const CurveNetwork lens = buildCurveNetwork(lensNetwork());
  const auto l2 = sharedEdgeMismatch(lens, m2);
  EXPECT_LE(l2.angle, 1e-9);
  EXPECT_GT(l2.curvature, 1e-2);
}

TEST(MultisidedPatch, TJunctionJoinsG2OnTheThroughCurveAndTheStem) {  // F8, rule (b)
  const CurveNetwork net = buildCurveNetwork(tJunctionNetwork());
  const auto m = sharedEdgeMismatch(net);
  expectG2(m, net.scale, 3);
}

TEST(MultisidedPatch, LensJoinsG2WithTheRegionAbove) {  // F11, rule (d)
  const CurveNetwork net = buildCurveNetwork(lensNetwork());
  expectG2(sharedEdgeMismatch(net), net.scale, 2);
}

TEST(MultisidedPatch, SubSurfaceMatchesTheNeighbourCurvesOnAdjacentEdges) {  // P3
  const CurveNetwork net = buildCurveNetwork(sphereOctantNetwork());
  const Face& face = net.faces[0];
  for (int i = 0; i < 3; ++i) {
    const FaceSide& side = face.sides[i];
    const FaceSide& prev = face.sides[(i + 2) % 3];
    const curvenet::Run& prevRun = net.runs[prev.run];
    for (double s : {0.2, 0.5, 0.9}) {
      const double v = s * prev.delta;
      const Jet u = Jet::constant(side.forward ? 0.0 : 1.0);
      const VectorJet sub = runSweep(net, side.run, u, Jet::constant(side.forward ? v : -v));
      // The previous side, v back from its end P_i.
      const double local = 1.0 - s;
      const double ur = prev.forward ? local : 1.0 - local;
      const Eigen::Vector3d expected = net.curves[prevRun.curve].evaluate(prevRun.tStart + prevRun.delta() * ur);
      EXPECT_LE((sub.v - expected).norm(), 1e-12 * net.scale);
    }
  }
}

TEST(MultisidedPatch, TranslationalNetworkIsReproducedForFourSides) {  // P9
  const CurveNetwork net = buildCurveNetwork(translationalNetwork());
  ASSERT_EQ(net.faces.size(), 1u);
  const Face& face = net.faces[0];
  ASSERT_EQ(face.sides.size(), 4u);
  const NGonDomain d(4);
  auto sidePointAt = [&](const FaceSide& s, double local) {
    const curvenet::Run& r = net.runs[s.run];
    const double u = s.forward ? local : 1.0 - local;
    return net.curves[r.curve].evaluate(r.tStart + r.delta() * u);
  };
  const Eigen::Vector3d p0 = net.vertices[face.sides[0].startVertex].position;
  double worst = 0.0;
  for (double x = -0.65; x <= 0.65; x += 0.13) {
    for (double y = -0.65; y <= 0.65; y += 0.13) {
      const Eigen::Vector2d p(x, y);
      const auto b = d.barycentric(p);
      const double ut = d.uTilde(0, b).v, dist = d.distance(0, b).v;
      // C_1(u) + C^_4(v): v = Delta_4 d_1 measured back along side 3 from P_0.
      const Eigen::Vector3d expected = sidePointAt(face.sides[0], ut) +
                                       (sidePointAt(face.sides[3], 1.0 - dist) - p0);
      worst = std::max(worst, (evaluatePatch(net, 0, d, p).v - expected).norm());
    }
  }
  EXPECT_LE(worst, 1e-12 * net.scale);
}

TEST(MultisidedPatch, CornerNormalConvergesToTheCurveTangentsNormal) {  // P8
  const CurveNetwork net = buildCurveNetwork(heightGridNetwork(3));
  const NGonDomain d(4);
  for (int k = 0; k < 4; ++k) {
    const int v = net.faces[0].sides[k].startVertex;
    const Eigen::Vector3d expected = net.vertices[v].normal;
    double previous = -1.0;
    for (double eps : {1e-2, 1e-3, 1e-4}) {
      const Eigen::Vector2d p = (1.0 - eps) * d.vertex(k);
      const double err = (patchNormal(evaluatePatch(net, 0, d, p)) - expected).norm();
      if (previous > 1e-10) {
        EXPECT_LE(err / previous, 0.2) << "eps " << eps;
      }
      previous = err;
    }
  }
}

TEST(MultisidedPatch, CyclicRelabellingWithRotatedDomainGivesTheSameSurface) {  // P10
  const CurveNetwork net = buildCurveNetwork(lensNetwork());
  CurveNetwork rotated = net;
  for (int f = 0; f < static_cast<int>(net.faces.size()); ++f) {
    auto& sides = rotated.faces[f].sides;
    std::rotate(sides.begin(), sides.begin() + 1, sides.end());
    const int n = static_cast<int>(sides.size());
    const NGonDomain d(n);
    const double th = -2 * std::numbers::pi / n;
    const Eigen::Matrix2d rot{{std::cos(th), -std::sin(th)}, {std::sin(th), std::cos(th)}};
    for (double x = -0.5; x <= 0.5; x += 0.25) {
      for (double y = -0.5; y <= 0.5; y += 0.25) {
        const Eigen::Vector2d p(x, y);
        EXPECT_LE((evaluatePatch(rotated, f, d, rot * p).v - evaluatePatch(net, f, d, p).v).norm(), 1e-12 * net.scale);
      }
    }
  }
}

TEST(MultisidedPatch, JetDerivativesMatchFiniteDifferences) {
  const CurveNetwork net = buildCurveNetwork(tJunctionNetwork());
  const Eigen::Vector2d p(0.1, -0.2), hx(1e-6, 0), hy(0, 1e-6);
  for (int f = 0; f < static_cast<int>(net.faces.size()); ++f) {
    const NGonDomain d(static_cast<int>(net.faces[f].sides.size()));
    const VectorJet q = evaluatePatch(net, f, d, p);
    const VectorJet qx1 = evaluatePatch(net, f, d, p + hx), qx0 = evaluatePatch(net, f, d, p - hx);
    const VectorJet qy1 = evaluatePatch(net, f, d, p + hy), qy0 = evaluatePatch(net, f, d, p - hy);
    EXPECT_LE((q.x - (qx1.v - qx0.v) / 2e-6).norm(), 1e-6);
    EXPECT_LE((q.y - (qy1.v - qy0.v) / 2e-6).norm(), 1e-6);
    EXPECT_LE((q.xx - (qx1.x - qx0.x) / 2e-6).norm(), 1e-5);
    EXPECT_LE((q.xy - (qy1.x - qy0.x) / 2e-6).norm(), 1e-5);
    EXPECT_LE((q.yy - (qy1.y - qy0.y) / 2e-6).norm(), 1e-5);
  }
}

TEST(MultisidedPatch, RejectsAMismatchedDomainAndExponent) {
  const CurveNetwork net = buildCurveNetwork(sphereOctantNetwork());
  EXPECT_THROW(evaluatePatch(net, 0, NGonDomain(4), {0, 0}), std::invalid_argument);
  PatchOptions o;
  o.blendingExponent = 0;
  EXPECT_THROW(evaluatePatch(net, 0, NGonDomain(3), {0, 0}, o), std::invalid_argument);
}

}  // namespace
}  // namespace ffdkit::geometry::curvenet
