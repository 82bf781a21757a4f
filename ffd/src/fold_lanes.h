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

/// G = det[H_u, H_v, H_w, H] (H = (w P, w), Lamousin & Waggenspack 1994) of up to kFoldLanes
/// cells of a rational lattice (foldLanesSupport), the polynomial of checkFolding's one-cell
/// rational path, with one lane per cell; scratch sized once (the minors of the Laplace expansion).
class RationalLanes {
 public:
  /// @param extraction per axis, per cell, the Bezier extraction matrix (fold_check.cpp).
  RationalLanes(const Lattice& lattice, const std::vector<Eigen::MatrixXd>* extraction);

  /// Computes cells[0 .. count) (count in [1, kFoldLanes]).
  void compute(const std::array<int, 3>* cells, int count);

  /// G's degree per axis (4p - 1).
  int degree() const { return degree_; }
  /// The smallest and the largest coefficient of G in lane `lane` after compute().
  double lowest(int lane) const { return lowest_[lane]; }
  double highest(int lane) const { return highest_[lane]; }  ///< see lowest()
  /// The smallest and the largest weight of lane `lane`'s window.
  double minWeight(int lane) const { return minWeight_[lane]; }
  double maxWeight(int lane) const { return maxWeight_[lane]; }  ///< see minWeight()
  /// Lane `lane`'s (degree + 1)^3 coefficients times `sign`, index i + (d+1) (j + (d+1) k).
  void coefficients(int lane, double sign, std::vector<double>& out) const;

 private:
  double* aligned();
  const double* coefficientData() const;

  const Lattice& lattice_;
  const std::vector<Eigen::MatrixXd>* extraction_;
  int degree_ = 0;
  std::vector<double> storage_;  // columns, minors and G, lane fastest, from a 64-byte boundary
  double lowest_[kFoldLanes] = {}, highest_[kFoldLanes] = {};
  double minWeight_[kFoldLanes] = {}, maxWeight_[kFoldLanes] = {};
};

}  // namespace ffdkit::ffd::detail
