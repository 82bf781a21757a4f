// Affine <-> affine bindings driven backwards (Kuriyama 1996, sec. 6.2.2: the reverse uses 1/gain; binding.h: the
// clamp bounds the `to` widget only when the binding drives it). Every expectation is written out
// from the lattice geometry, not read back through the model.
#include <numbers>

#include <gtest/gtest.h>

#include "ffdkit/widgets/thesis_examples.h"
#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::widgets {
namespace {

using std::numbers::pi;

// A 3x2x2 lattice in the unit box: rest x of point (i, j, k) is i / 2. Translate widgets (+x) on
// the points (0,0,0) (flat index 0) and (2,1,1) (flat 11), bound from -> to with `rule`.
struct TwoPoints {
  WidgetModel model;
  WidgetId lattice, from, to;
};

TwoPoints twoBoundPoints(const ConversionRule& rule) {
  TwoPoints t;
  t.lattice = t.model.addLattice("box", Eigen::Vector3i(3, 2, 2));
  t.from = t.model.addAffine(t.model.addCell(t.lattice, CellSpec::point(0, 0, 0)), AffineKind::Translate, "from");
  t.to = t.model.addAffine(t.model.addCell(t.lattice, CellSpec::point(2, 1, 1)), AffineKind::Translate, "to");
  t.model.bind(t.from, t.to, rule);
  return t;
}

// Every control point but 0 and 11 stays at rest; 0 and 11 moved along x by the given amounts.
void expectPointsMoved(const TwoPoints& t, double dxFrom, double dxTo) {
  const Eigen::MatrixX3d& p = t.model.controlPoints(t.lattice);
  const Eigen::MatrixX3d& rest = t.model.restPoints(t.lattice);
  for (Eigen::Index r = 0; r < p.rows(); ++r) {
    const double dx = r == 0 ? dxFrom : r == 11 ? dxTo : 0.0;
    EXPECT_NEAR(p(r, 0), rest(r, 0) + dx, 1e-14) << "point " << r;
    EXPECT_NEAR(p(r, 1), rest(r, 1), 1e-14) << "point " << r;
    EXPECT_NEAR(p(r, 2), rest(r, 2), 1e-14) << "point " << r;
  }
  EXPECT_NEAR(p(0, 0), dxFrom, 1e-14);
  EXPECT_NEAR(p(11, 0), 1.0 + dxTo, 1e-14);
}

TEST(BindingPropagation, ForwardUsesTheGainAndTheClampOfTheTarget) {
  TwoPoints t = twoBoundPoints(ConversionRule(0.5, VariationRange{-0.2, 0.3}));
  t.model.applyVariation(t.from, 0.4);  // 0.5 * 0.4 = 0.2, inside the clamp
  EXPECT_NEAR(t.model.variation(t.to), 0.2, 1e-15);
  expectPointsMoved(t, 0.4, 0.2);
  t.model.applyVariation(t.from, 0.6);  // accumulated 1.0 -> 0.5, stopped at 0.3
  EXPECT_NEAR(t.model.variation(t.to), 0.3, 1e-15);
  expectPointsMoved(t, 1.0, 0.3);
  t.model.applyVariation(t.from, -2.0);  // accumulated -1.0 -> -0.5, stopped at -0.2
  EXPECT_NEAR(t.model.variation(t.from), -1.0, 1e-15);
  EXPECT_NEAR(t.model.variation(t.to), -0.2, 1e-15);
  expectPointsMoved(t, -1.0, -0.2);
}

TEST(BindingPropagation, ReverseDividesByTheGainAndIgnoresTheTargetClamp) {
  TwoPoints t = twoBoundPoints(ConversionRule(0.5, VariationRange{-0.2, 0.3}));
  // Driving `to` drives `from` by delta / gain = 2 delta; the clamp belongs to the forward
  // direction, so neither the dragged `to` nor the driven `from` is stopped at 0.3.
  t.model.applyVariation(t.to, 0.4);
  EXPECT_NEAR(t.model.variation(t.to), 0.4, 1e-15);
  EXPECT_NEAR(t.model.variation(t.from), 0.8, 1e-15);
  expectPointsMoved(t, 0.8, 0.4);
  t.model.applyVariation(t.to, -1.0);
  EXPECT_NEAR(t.model.variation(t.from), -1.2, 1e-15);
  expectPointsMoved(t, -1.2, -0.6);
  // One-way: the reverse no longer propagates.
  t.model.setOneWay(t.model.bindingsOf(t.to).back(), true);
  t.model.applyVariation(t.to, 0.5);
  EXPECT_NEAR(t.model.variation(t.from), -1.2, 1e-15);
  expectPointsMoved(t, -1.2, -0.1);
}

TEST(BindingPropagation, AChainMultipliesGainsForwardAndDividesThemBackwards) {
  // a -(gain 0.5)-> b -(gain 4, clamp [0, 1] on c)-> c, three translate widgets on points of one lattice.
  WidgetModel m;
  const WidgetId lat = m.addLattice("box", Eigen::Vector3i(3, 2, 2));
  const WidgetId a = m.addAffine(m.addCell(lat, CellSpec::point(0, 0, 0)), AffineKind::Translate, "a");
  const WidgetId b = m.addAffine(m.addCell(lat, CellSpec::point(1, 0, 0)), AffineKind::Translate, "b");
  const WidgetId c = m.addAffine(m.addCell(lat, CellSpec::point(2, 0, 0)), AffineKind::Translate, "c");
  m.bind(a, b, ConversionRule(0.5));
  m.bind(b, c, ConversionRule(4.0, VariationRange{0.0, 1.0}));
  m.applyVariation(a, 0.3);  // b = 0.15, c = 0.6
  EXPECT_NEAR(m.variation(b), 0.15, 1e-15);
  EXPECT_NEAR(m.variation(c), 0.6, 1e-15);
  m.applyVariation(a, 0.5);  // b = 0.4, c = 1.6 -> clamped to 1
  EXPECT_NEAR(m.variation(b), 0.4, 1e-15);
  EXPECT_NEAR(m.variation(c), 1.0, 1e-15);
  // Backwards from c: b gets delta / 4, a gets that / 0.5.
  m.applyVariation(c, -0.8);
  EXPECT_NEAR(m.variation(c), 0.2, 1e-15);
  EXPECT_NEAR(m.variation(b), 0.2, 1e-15);
  EXPECT_NEAR(m.variation(a), 0.4, 1e-15);
  const Eigen::MatrixX3d& p = m.controlPoints(lat);
  EXPECT_NEAR(p(0, 0), 0.4, 1e-14);
  EXPECT_NEAR(p(1, 0), 0.5 + 0.2, 1e-14);
  EXPECT_NEAR(p(2, 0), 1.0 + 0.2, 1e-14);
}

TEST(BindingPropagation, DrivingThePressTurnsTheHandleByTheInversePitch) {
  // Fig. 6-10 backwards: the screw's gain is pitch / (2 pi) units per rad, so pushing the face
  // down by d turns the handle by 2 pi d / pitch, and the press's clamp does not stop a direct drag.
  Fig610 fig = buildFig610(/*pitch=*/0.1, VariationRange{0.0, 0.15});
  WidgetModel& m = fig.model;
  m.applyVariation(fig.press, 0.05);
  EXPECT_NEAR(m.variation(fig.handle), pi, 1e-13);
  m.applyVariation(fig.press, 0.25);
  EXPECT_NEAR(m.variation(fig.press), 0.3, 1e-15);
  EXPECT_NEAR(m.variation(fig.handle), 6.0 * pi, 1e-12);
  const Eigen::MatrixX3d& p = m.controlPoints(fig.lattice);
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    EXPECT_NEAR(p(i, 2), m.restPoints(fig.lattice)(i, 2) > 0.5 ? 1.0 - 0.3 : 0.0, 1e-14) << i;
  }
  // Turning the handle back: the forward clamp now holds the press inside [0, 0.15].
  m.applyVariation(fig.handle, -2.0 * pi);  // would be 0.3 - 0.1 = 0.2
  EXPECT_NEAR(m.variation(fig.press), 0.2, 1e-15);
}

}  // namespace
}  // namespace ffdkit::widgets
