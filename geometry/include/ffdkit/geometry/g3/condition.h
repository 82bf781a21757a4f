#pragma once

#include <functional>
#include <string>

#include <Eigen/Core>

namespace ffdkit::geometry::g3 {

/// Index meaning "the last point p_n" / "the last span" in a Condition, so that conditions can
/// be written before the point count is known.
inline constexpr int kLast = -1;

/// A user-supplied side condition g(v) = 0 (B8). v = (Delta s_0..Delta s_{n-1}, d_{-1}..d_{n+1})
/// in the paper's text order (Kuroda et al. 1997, sec. 3); the function returns g(v) and writes
/// dg/dv (1 x (2n+3)) into gradient.
using CustomConditionFunction =
    std::function<double(const Eigen::VectorXd& v, Eigen::Ref<Eigen::RowVectorXd> gradient)>;

/// One boundary or side condition of the G3 interpolation system, as rows g(v) = 0 stacked
/// under the 2n interpolation equations (Kuroda et al. 1997, sec. 3, table B1..B10).
/// Plain data except for Custom. At most 3 rows in total make the system square; fewer leave a
/// one-parameter family (min-norm Newton as in Kuroda et al. 1997, sec. 4).
struct Condition {
  /// The kind of condition (the rows of Kuroda et al. 1997, table B1..B10).
  enum class Kind {
    TangentAngle,       ///< B1: psi(s_index) = value (rad); matched on the nearest 2 pi branch
    Curvature,          ///< B2/B3: kappa(s_index) = value (1/length)
    RadiusOfCurvature,  ///< B4: rho(s_index) = value, as Delta s - 3 rho (b_{3i+1} - b_{3i}) = 0
    ClothoidSpan,       ///< B5: span `index` has linear curvature (a_3 = 0)
    CircularArcSpan,    ///< B6: span `index` has constant curvature (a_3 = a_2 = 0): 2 rows
    Length,             ///< B7: sum of Delta s_i for spans index..lastIndex = value
    NaturalEnds,        ///< B10, the appendix default: d_0 - d_{-1} = 0, d_{n+1} - d_n = 0: 2 rows
    Custom,             ///< B8: custom(v) = 0
  };

  Kind kind = Kind::NaturalEnds;  ///< which condition
  int index = 0;       ///< point index 0..n or span index 0..n-1; kLast for the last one
  int lastIndex = kLast;  ///< Length only: last span of the summed range (inclusive)
  double value = 0.0;  ///< the target (rad, 1/length or length)
  CustomConditionFunction custom;  ///< Custom only
  std::string name;                ///< Custom only, for messages

  /// B1 at point i (0..n or kLast).
  static Condition tangentAngle(int pointIndex, double radians) { return {Kind::TangentAngle, pointIndex, kLast, radians, {}, {}}; }
  /// B2 (ends) / B3 (interior): curvature at point i.
  static Condition curvature(int pointIndex, double kappa) { return {Kind::Curvature, pointIndex, kLast, kappa, {}, {}}; }
  /// B4: radius of curvature at point i, written without dividing by kappa (sec. 3).
  static Condition radiusOfCurvature(int pointIndex, double rho) { return {Kind::RadiusOfCurvature, pointIndex, kLast, rho, {}, {}}; }
  /// B5: span `span` has linear curvature (a clothoid).
  static Condition clothoidSpan(int span) { return {Kind::ClothoidSpan, span, kLast, 0.0, {}, {}}; }
  /// B6: span `span` has constant curvature (a circular arc).
  static Condition circularArcSpan(int span) { return {Kind::CircularArcSpan, span, kLast, 0.0, {}, {}}; }
  /// B7: the total arc length is `length`.
  static Condition totalLength(double length) { return {Kind::Length, 0, kLast, length, {}, {}}; }
  /// B7: spans firstSpan..lastSpan have arc length `length` together.
  static Condition partialLength(int firstSpan, int lastSpan, double length) { return {Kind::Length, firstSpan, lastSpan, length, {}, {}}; }
  /// B10: natural ends, the appendix default.
  static Condition naturalEnds() { return {Kind::NaturalEnds, 0, kLast, 0.0, {}, {}}; }
  /// B8: a condition custom(v) = 0 of your own, named `label` in messages.
  static Condition customCondition(std::string label, CustomConditionFunction function) {
    return {Kind::Custom, 0, kLast, 0.0, std::move(function), std::move(label)};
  }

  /// Rows this condition adds to the system (2 for CircularArcSpan and NaturalEnds, else 1).
  int rowCount() const { return kind == Kind::CircularArcSpan || kind == Kind::NaturalEnds ? 2 : 1; }
};

}  // namespace ffdkit::geometry::g3
