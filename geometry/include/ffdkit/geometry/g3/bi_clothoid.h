#pragma once

#include <array>

#include <Eigen/Core>

#include "ffdkit/geometry/g3/clothoid_arc.h"

namespace ffdkit::geometry::g3 {

/// End data a bi-clothoid must match: points, tangent angles (rad, unwrapped) and curvatures.
struct BiClothoidEnds {
  Eigen::Vector2d startPoint = Eigen::Vector2d::Zero();  ///< start point
  Eigen::Vector2d endPoint = Eigen::Vector2d::Zero();  ///< end point
  double startAngle = 0.0;  ///< tangent angle at the start (rad)
  double endAngle = 0.0;  ///< tangent angle at the end (rad)
  double startCurvature = 0.0;  ///< curvature at the start (1/length)
  double endCurvature = 0.0;  ///< curvature at the end (1/length)
};

/// Options of fitBiClothoid's Newton iteration.
struct BiClothoidOptions {
  double tolerance = 1e-13;  ///< max chord residual / |chord| (Kuroda et al. 1997, sec. 6)
  int maxIterations = 20;    ///< Newton iterations
};

/// The fitted bi-clothoid and how the fit went.
struct BiClothoidResult {
  std::array<ClothoidArc, 2> arcs;  ///< G2-joined: arcs[1] starts where arcs[0] ends
  bool converged = false;  ///< the residual reached the tolerance
  int iterations = 0;  ///< Newton iterations taken
  double residual = 0.0;  ///< |sigma_0 I_0 + sigma_1 I_1 - chord| at the result
};

/// Two clothoid arcs of lengths sigma0, sigma1 matching the end angles and curvatures and
/// joined with continuous curvature, starting at ends.startPoint. Where they end depends on the
/// lengths; fitBiClothoid chooses them so that it is ends.endPoint. Ordinates
/// c_0 = psi_a, c_1 = c_0 + kappa_a sigma_0 / 2, c_3 = c_4 - kappa_b sigma_1 / 2,
/// c_2 = (c_3 sigma_0 + c_1 sigma_1) / (sigma_0 + sigma_1), c_4 = psi_b.
/// The factor 1/2 corrects the misprinted "2 kappa" of Kuroda et al. 1997, sec. 6 (the Mathematica
/// code of app. 1 has 1/2).
/// @throws G3InputError unless sigma0, sigma1 > 0 and finite.
std::array<ClothoidArc, 2> makeBiClothoid(const BiClothoidEnds& ends, double sigma0, double sigma1);

/// Solves sigma_0 int e^{i psi_0} + sigma_1 int e^{i psi_1} = chord (Kuroda et al. 1997, sec. 6) by
/// Newton with the analytic 2x2 Jacobian and a pseudo-inverse step (singular when the data are a
/// single clothoid), from sigma_0 = sigma_1 = lengthGuess / 2 (app. 1), halving steps to keep sigma
/// > 0. Never throws for unreachable data: converged = false then.
/// @throws G3InputError for non-finite ends, coincident end points or lengthGuess <= 0.
BiClothoidResult fitBiClothoid(const BiClothoidEnds& ends, double lengthGuess, const BiClothoidOptions& options = {});

}  // namespace ffdkit::geometry::g3
