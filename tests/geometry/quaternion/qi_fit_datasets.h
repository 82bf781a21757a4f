#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/geometry/quaternion/qi_chain.h"

namespace ffdkit::geometry::quaternion::testdata {

/// A synthetic stand-in for the data of Sakiyama et al. 2001, sec. 3.7, with its breaks and (when known) its true u.
struct FitDataset {
  Eigen::MatrixX3d points;
  std::vector<int> breaks;
  Eigen::VectorXd trueU;  ///< empty when unknown
};

/// Adds a(2r - 1), r = mt19937(seed)() / 2^32, to each coordinate in point order (x, y[, z]).
void addUniformNoise(Eigen::MatrixX3d& points, double a, std::uint32_t seed, bool planar);

FitDataset sine(const std::vector<int>& breaks);  ///< D-SINE
FitDataset sineNoisy();                           ///< D-SINE-N, breaks B1
QiChain chain2dTruth();                           ///< the D-CHAIN2D ground-truth chain
FitDataset chain2d();
FitDataset chain2dNoisy();
QiChain chain3dTruth();
FitDataset chain3d();
FitDataset chain3dNoisy();
FitDataset helix();
FitDataset spiral(int segments);       ///< D-SPIRAL, M = 6 or 16
FitDataset spiralNoisy(int segments);  ///< D-SPIRAL-N, M = 6, 8 or 16

}  // namespace ffdkit::geometry::quaternion::testdata
