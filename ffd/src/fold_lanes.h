// Internal to ffd/: det J's Bernstein coefficients of several lattice cells at once (one SIMD
// lane per cell), the fast path of checkFolding for lattices whose three axes share a degree 1..3.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/ffd/lattice.h"

namespace ffdkit::ffd::detail {

/// Cells computed together: one 512-bit vector of doubles (two AVX2 or four SSE2 registers).
constexpr int kFoldLanes = 8;

/// True when checkFolding's batched products apply: the three axes have the same degree, 1 to 3.
bool foldLanesSupport(const Lattice& lattice);

/// det J's Bernstein coefficients of up to kFoldLanes cells of one lattice (foldLanesSupport), the
/// same polynomial as jacobianDeterminantPatch's: the cells' Bezier nets are gathered into lanes,
/// the derivative nets scaled by their binomials, and the two products of nets (X_v x X_w, then
/// X_u . that) accumulate one output row at a time in registers, every size a compile-time
/// constant. Reused across calls: sized once, no allocation per batch.
class DeterminantLanes {
 public:
  /// @param extraction per axis, per cell, the Bezier extraction matrix (fold_check.cpp).
  DeterminantLanes(const Lattice& lattice, const std::vector<Eigen::MatrixXd>* extraction);

  /// Computes cells[0 .. count) (count in [1, kFoldLanes]).
  void compute(const std::array<int, 3>* cells, int count);

  /// det J's degree per axis (3p - 1).
  int degree() const { return degree_; }
  /// The smallest and the largest coefficient of lane `lane` after compute().
  double lowest(int lane) const { return lowest_[lane]; }
  double highest(int lane) const { return highest_[lane]; }  ///< see lowest()
  /// Lane `lane`'s (degree + 1)^3 coefficients times `sign`, index i + (d+1) (j + (d+1) k).
  void coefficients(int lane, double sign, std::vector<double>& out) const;

 private:
  const Lattice& lattice_;
  const std::vector<Eigen::MatrixXd>* extraction_;
  int degree_ = 0;
  std::vector<double> coefficients_;  // (degree + 1)^3 x kFoldLanes, lane fastest
  double lowest_[kFoldLanes] = {}, highest_[kFoldLanes] = {};
};

}  // namespace ffdkit::ffd::detail
