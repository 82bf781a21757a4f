#pragma once
// Input points of the paper's examples (Kuroda et al. 1997, app. 2) and the synthetic
// exactness cases S1-S3 (curves of the family, so they must be reproduced).

#include <Eigen/Core>

namespace ffdkit::geometry::g3::testdata {

Eigen::MatrixX2d figure2Points();  ///< Figs. 1 and 2, n = 7 (app. 2)
Eigen::MatrixX2d figure3Points();  ///< n = 10 (app. 2)
Eigen::MatrixX2d figure4Points();  ///< n = 20 (app. 2)
Eigen::MatrixX2d figure5Points();  ///< n = 11 (app. 2)

/// S1: psi(s) = 0.3 - 0.25 s + 0.03 s^2 - 0.001 s^3, start (1, 2).
double s1Angle(double s);
double s1Curvature(double s);
double s1CurvatureDerivative(double s);
/// The sample arc lengths {0, 1.5, 3.2, 5.0, 6.1, 8.3, 10}.
Eigen::VectorXd s1Knots();
/// The points, 12 decimals.
Eigen::MatrixX2d s1Points();
/// de Boor ordinates of a global cubic c0 + c1 s + c2 s^2 + c3 s^3 on the given knots, by the
/// blossom (Marsden): d_j = P[s_{j-1}, s_j, s_{j+1}] with clamped end knots.
Eigen::VectorXd cubicDeBoor(const Eigen::Vector4d& coefficients, const Eigen::VectorXd& knots);

}  // namespace ffdkit::geometry::g3::testdata
