#include "minimum_norm.h"

#include <Eigen/QR>

namespace ffdkit::ffd::detail {

Eigen::MatrixX3d minimumNormSolve(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  return Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(A).solve(B);
}

Eigen::VectorXd minimumNormSolve(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  return Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(A).solve(b);
}

}  // namespace ffdkit::ffd::detail
