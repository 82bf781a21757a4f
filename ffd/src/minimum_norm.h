// Internal to ffd/: the minimum-norm solution of a small system, compiled once.
#pragma once

#include <Eigen/Core>

namespace ffdkit::ffd::detail {

/// X = A^+ B (B with three columns), the minimum-norm least-squares solution of A X = B by
/// Eigen's complete orthogonal decomposition of A (square, small: a Gram matrix of constraint
/// rows). With dependent rows it is the pseudo-inverse's solution (Hsu, Hughes & Kaufman 1992 use
/// it for direct manipulation; the shape constraints' Newton steps for the same reason). Defined
/// once, in minimum_norm.cpp: the decomposition is instantiated and optimized in one translation
/// unit instead of in each of its users.
Eigen::MatrixX3d minimumNormSolve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);
/// The same for one right-hand side.
Eigen::VectorXd minimumNormSolve(const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

}  // namespace ffdkit::ffd::detail
