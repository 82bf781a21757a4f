#include "ffdkit/ffd/direct_manipulation.h"

#include <string>

#include "minimum_norm.h"

namespace ffdkit::ffd {

std::vector<BasisWeight> basisWeights(const Lattice& lattice, const Eigen::Vector3d& uvw) {
  if (!uvw.allFinite()) throw LatticeError("basisWeights: parameters must be finite");
  // The same cells and basis values as Lattice::evaluate (eq. (6.1)).
  constexpr int kMax = 33;
  double N[3][kMax];
  int cell[3];
  for (int a = 0; a < 3; ++a) {
    const AxisSpline& axis = lattice.axis(a);
    if (axis.degree() + 1 > kMax) throw LatticeError("basisWeights: degree above 32");
    cell[a] = axis.cellOf(uvw[a]);
    axis.basis(cell[a], uvw[a], N[a]);
  }
  std::vector<BasisWeight> out;
  const int pu = lattice.axis(0).degree(), pv = lattice.axis(1).degree(), pw = lattice.axis(2).degree();
  out.reserve(static_cast<std::size_t>((pu + 1) * (pv + 1) * (pw + 1)));
  for (int c = 0; c <= pw; ++c) {
    const int k = lattice.axis(2).controlIndex(cell[2], c);
    for (int b = 0; b <= pv; ++b) {
      const int j = lattice.axis(1).controlIndex(cell[1], b);
      for (int a = 0; a <= pu; ++a) {
        const int i = lattice.axis(0).controlIndex(cell[0], a);
        out.push_back({lattice.index(i, j, k), N[0][a] * N[1][b] * N[2][c]});
      }
    }
  }
  if (lattice.isRational()) {
    // X = sum R P with R = w B / sum w B (Lamousin & Waggenspack 1994): linear in P for fixed weights.
    double sum = 0.0;
    for (BasisWeight& b : out) {
      b.weight *= lattice.weight(b.point);
      sum += b.weight;
    }
    for (BasisWeight& b : out) b.weight /= sum;
  }
  return out;
}

Eigen::MatrixX3d leastNormControlChange(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& uvw,
                                        const Eigen::Ref<const Eigen::MatrixX3d>& displacements) {
  if (uvw.rows() != displacements.rows())
    throw LatticeError("leastNormControlChange: " + std::to_string(uvw.rows()) + " parameters but " +
                       std::to_string(displacements.rows()) + " displacements");
  if (!displacements.allFinite()) throw LatticeError("leastNormControlChange: displacements must be finite");
  const Eigen::Index k = uvw.rows();
  Eigen::MatrixX3d change = Eigen::MatrixX3d::Zero(lattice.pointCount(), 3);
  if (k == 0) return change;
  // Rows of B as sparse weight lists; B B^T from their overlaps (a k x k system, k small).
  std::vector<std::vector<BasisWeight>> rows;
  rows.reserve(static_cast<std::size_t>(k));
  for (Eigen::Index r = 0; r < k; ++r) rows.push_back(basisWeights(lattice, uvw.row(r).transpose()));
  Eigen::VectorXd dense = Eigen::VectorXd::Zero(lattice.pointCount());
  Eigen::MatrixXd gram(k, k);
  for (Eigen::Index r = 0; r < k; ++r) {
    for (const BasisWeight& w : rows[static_cast<std::size_t>(r)]) dense[w.point] += w.weight;
    for (Eigen::Index s = 0; s < k; ++s) {
      double dot = 0.0;
      for (const BasisWeight& w : rows[static_cast<std::size_t>(s)]) dot += dense[w.point] * w.weight;
      gram(r, s) = dot;
    }
    for (const BasisWeight& w : rows[static_cast<std::size_t>(r)]) dense[w.point] = 0.0;
  }
  // Y = (B B^T)^+ D; the complete orthogonal decomposition gives the minimum-norm solution when
  // constraints are dependent (HHK 1992 use the pseudo-inverse for the same reason).
  const Eigen::MatrixX3d y = detail::minimumNormSolve(gram, Eigen::MatrixXd(displacements));
  for (Eigen::Index r = 0; r < k; ++r)
    for (const BasisWeight& w : rows[static_cast<std::size_t>(r)]) change.row(w.point) += w.weight * y.row(r);
  return change;
}

}  // namespace ffdkit::ffd
