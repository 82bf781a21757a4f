#include "ffdkit/cad/bernstein_composition.h"

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/LU>

#include "ffdkit/cad/cad_error.h"
#include "ffdkit/ffd/bernstein_basis.h"

namespace ffdkit::cad {

namespace {

/// C(n, k) for n < 256, from Pascal's triangle (exact in double up to n = 56, relative error
/// 1e-16 beyond; the composed degrees stay far below that).
double binomial(int n, int k) {
  static const std::vector<std::vector<double>> table = [] {
    std::vector<std::vector<double>> t(256);
    for (int row = 0; row < 256; ++row) {
      t[row].assign(row + 1, 1.0);
      for (int col = 1; col < row; ++col) t[row][col] = t[row - 1][col - 1] + t[row - 1][col];
    }
    return t;
  }();
  if (n < 0 || n >= 256 || k < 0 || k > n) throw CadError("degree " + std::to_string(n) + " is beyond the composition's table");
  return table[n][k];
}

/// A bivariate polynomial in the scaled Bernstein basis s^a (1-s)^(du-a) t^b (1-t)^(dv-b): its
/// coefficients are the Bernstein coefficients times C(du, a) C(dv, b), so that the product of two
/// such polynomials is the convolution of their coefficient arrays. Row a + (du+1)*b, one column
/// per component.
struct ScaledPoly {
  int du = 0;
  int dv = 0;
  Eigen::MatrixXd c;

  static ScaledPoly constant(double value) {
    ScaledPoly p;
    p.c = Eigen::MatrixXd::Constant(1, 1, value);
    return p;
  }
  static ScaledPoly zero(int du, int dv, int components) {
    ScaledPoly p;
    p.du = du;
    p.dv = dv;
    p.c = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(du + 1) * (dv + 1), components);
    return p;
  }
};

/// x * y, y scalar (one component): the 2D convolution of the scaled coefficients.
ScaledPoly multiply(const ScaledPoly& x, const ScaledPoly& y) {
  ScaledPoly out = ScaledPoly::zero(x.du + y.du, x.dv + y.dv, static_cast<int>(x.c.cols()));
  const int nu = out.du + 1;
  for (int yb = 0; yb <= y.dv; ++yb)
    for (int ya = 0; ya <= y.du; ++ya) {
      const double f = y.c(ya + (y.du + 1) * yb, 0);
      if (f == 0.0) continue;
      for (int xb = 0; xb <= x.dv; ++xb)
        for (int xa = 0; xa <= x.du; ++xa)
          out.c.row((xa + ya) + nu * (xb + yb)) += f * x.c.row(xa + (x.du + 1) * xb);
    }
  return out;
}

/// out += x, same degrees.
void accumulate(ScaledPoly& out, const ScaledPoly& x) { out.c += x.c; }

/// The poles of the patch as scaled homogeneous polynomials: W and, per axis a, Uh_a = W * (u_a).
void homogeneousParameters(const BernsteinVolume& volume, const BezierPatch& patch, ScaledPoly& weight,
                           ScaledPoly (&axes)[3]) {
  const int p = patch.degreeU;
  const int q = patch.degreeV;
  weight = ScaledPoly::zero(p, q, 1);
  for (auto& axis : axes) axis = ScaledPoly::zero(p, q, 1);
  const bool rational = patch.weights.size() > 0;
  for (int b = 0; b <= q; ++b)
    for (int a = 0; a <= p; ++a) {
      const Eigen::Index row = a + (p + 1) * b;
      const double w = rational ? patch.weights[row] : 1.0;
      const double scale = binomial(p, a) * binomial(q, b);
      const Eigen::Vector3d uvw = volume.toParameter * Eigen::Vector3d(patch.poles.row(row).transpose());
      weight.c(row, 0) = w * scale;
      for (int axis = 0; axis < 3; ++axis) axes[axis].c(row, 0) = w * uvw[axis] * scale;
    }
}

/// T_i = C(n, i) Uh^i (W - Uh)^(n-i), i = 0..n (scaled): the Bernstein polynomials of one lattice
/// axis composed with the patch, times W^n.
std::vector<ScaledPoly> composedBasis(const ScaledPoly& weight, const ScaledPoly& uh, int n) {
  ScaledPoly vh = weight;
  vh.c -= uh.c;
  std::vector<ScaledPoly> upow{ScaledPoly::constant(1.0)};
  std::vector<ScaledPoly> vpow{ScaledPoly::constant(1.0)};
  for (int i = 1; i <= n; ++i) {
    upow.push_back(multiply(upow.back(), uh));
    vpow.push_back(multiply(vpow.back(), vh));
  }
  std::vector<ScaledPoly> basis;
  for (int i = 0; i <= n; ++i) {
    ScaledPoly t = multiply(upow[i], vpow[n - i]);
    t.c *= binomial(n, i);
    basis.push_back(std::move(t));
  }
  return basis;
}

void checkPatch(const BezierPatch& patch) {
  if (patch.degreeU < 0 || patch.degreeV < 0) throw CadError("a Bezier patch needs degrees >= 0");
  if (patch.poles.rows() != patch.poleCount())
    throw CadError("a Bezier patch of degree (" + std::to_string(patch.degreeU) + ", " + std::to_string(patch.degreeV) +
                   ") needs " + std::to_string(patch.poleCount()) + " poles, got " + std::to_string(patch.poles.rows()));
  if (!patch.poles.allFinite()) throw CadError("a Bezier patch has a non-finite pole");
  if (patch.weights.size() != 0) {
    if (patch.weights.size() != patch.poleCount()) throw CadError("a rational Bezier patch needs one weight per pole");
    for (Eigen::Index i = 0; i < patch.weights.size(); ++i)
      if (!(patch.weights[i] > 0.0) || !std::isfinite(patch.weights[i]))
        throw CadError("a rational Bezier patch has weight " + std::to_string(patch.weights[i]) + " (must be > 0)");
  }
}

}  // namespace

Eigen::Vector3d BezierPatch::evaluate(double s, double t) const {
  const bool rational = weights.size() > 0;
  // de Casteljau on (w P, w) along u for every row b, then along v.
  std::vector<Eigen::Vector4d> rows(degreeV + 1);
  std::vector<Eigen::Vector4d> work(degreeU + 1);
  for (int b = 0; b <= degreeV; ++b) {
    for (int a = 0; a <= degreeU; ++a) {
      const Eigen::Index row = a + (degreeU + 1) * b;
      const double w = rational ? weights[row] : 1.0;
      work[a] << w * poles.row(row).transpose(), w;
    }
    for (int level = degreeU; level > 0; --level)
      for (int a = 0; a < level; ++a) work[a] = (1.0 - s) * work[a] + s * work[a + 1];
    rows[b] = work[0];
  }
  for (int level = degreeV; level > 0; --level)
    for (int b = 0; b < level; ++b) rows[b] = (1.0 - t) * rows[b] + t * rows[b + 1];
  return rows[0].head<3>() / rows[0][3];
}

Eigen::Vector3d BernsteinVolume::evaluate(const Eigen::Vector3d& world) const {
  const Eigen::Vector3d uvw = toParameter * world;
  const Eigen::VectorXd bu = ffd::bernsteinBasis(degrees[0], uvw[0]);
  const Eigen::VectorXd bv = ffd::bernsteinBasis(degrees[1], uvw[1]);
  const Eigen::VectorXd bw = ffd::bernsteinBasis(degrees[2], uvw[2]);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Index row = 0;
  for (int k = 0; k <= degrees[2]; ++k)
    for (int j = 0; j <= degrees[1]; ++j)
      for (int i = 0; i <= degrees[0]; ++i, ++row) sum += bu[i] * bv[j] * bw[k] * points.row(row).transpose();
  return sum;
}

BernsteinVolume BernsteinVolume::fromLattice(const ffd::Lattice& lattice) {
  for (int axis = 0; axis < 3; ++axis)
    if (lattice.basis(axis).kind != ffd::AxisBasis::Kind::Bernstein)
      throw CadError("exact CAD deformation needs a Bernstein lattice; axis " + std::to_string(axis) +
                     " is a B-spline (its cells are polynomials of their own: fromLatticeCell)");
  if (!lattice.restIsAffine())
    throw CadError("exact CAD deformation needs a lattice whose rest shape is a box (an affine rest map)");
  BernsteinVolume volume;
  volume.degrees = lattice.counts().array() - 1;
  volume.points = (lattice.frame() * lattice.controlPoints().transpose()).transpose();
  // local = frame^-1 world; uvw = A^-1 (local - b)
  Eigen::Affine3d toLocalParameter = Eigen::Affine3d::Identity();
  toLocalParameter.linear() = lattice.restAffineLinear().inverse();
  toLocalParameter.translation() = -(toLocalParameter.linear() * lattice.restAffineOffset());
  volume.toParameter = toLocalParameter * lattice.frame().inverse();
  return volume;
}

namespace {

/// C[r][m]: the r-th basis function non-zero on `cell` of `axis`, in the Bernstein basis of the
/// axis's degree over the cell (from its values at degree+1 points of the cell).
Eigen::MatrixXd cellExtraction(const ffd::AxisSpline& axis, int cell) {
  const int p = axis.degree();
  const double a = axis.cellMin(cell), b = axis.cellMax(cell);
  Eigen::MatrixXd bernstein(p + 1, p + 1);  // [sample m][Bernstein l]
  Eigen::MatrixXd values(p + 1, p + 1);     // [sample m][basis r]
  std::vector<double> row(p + 1);
  for (int m = 0; m <= p; ++m) {
    const double t = double(m) / p;
    bernstein.row(m) = ffd::bernsteinBasis(p, t).transpose();
    axis.basis(cell, a + (b - a) * t, row.data());
    for (int r = 0; r <= p; ++r) values(m, r) = row[r];
  }
  return bernstein.fullPivLu().solve(values).transpose();  // C^T = B^-1 V
}

}  // namespace

BernsteinVolume BernsteinVolume::fromLatticeCell(const ffd::Lattice& lattice, const Eigen::Vector3i& cell) {
  if (!lattice.restIsAffine())
    throw CadError("exact CAD deformation needs a lattice whose rest shape is a box (an affine rest map)");
  Eigen::MatrixXd extraction[3];
  BernsteinVolume volume;
  Eigen::Affine3d toCell = Eigen::Affine3d::Identity();
  for (int a = 0; a < 3; ++a) {
    const ffd::AxisSpline& axis = lattice.axis(a);
    if (axis.periodic()) throw CadError("exact CAD deformation needs clamped lattice axes; axis " + std::to_string(a) + " is periodic");
    if (cell[a] < 0 || cell[a] >= axis.cellCount())
      throw CadError("lattice cell " + std::to_string(cell[a]) + " on axis " + std::to_string(a) + " is out of range");
    extraction[a] = cellExtraction(axis, cell[a]);
    volume.degrees[a] = axis.degree();
    const double lo = axis.cellMin(cell[a]), hi = axis.cellMax(cell[a]);
    toCell.linear()(a, a) = 1.0 / (hi - lo);
    toCell.translation()[a] = -lo / (hi - lo);
  }
  const Eigen::Vector3i n = volume.degrees;
  volume.points = Eigen::MatrixX3d::Zero(static_cast<Eigen::Index>(n[0] + 1) * (n[1] + 1) * (n[2] + 1), 3);
  const Eigen::MatrixX3d world = (lattice.frame() * lattice.controlPoints().transpose()).transpose();
  for (int rk = 0; rk <= n[2]; ++rk)
    for (int rj = 0; rj <= n[1]; ++rj)
      for (int ri = 0; ri <= n[0]; ++ri) {
        const Eigen::RowVector3d point = world.row(lattice.index(lattice.axis(0).controlIndex(cell[0], ri),
                                                                 lattice.axis(1).controlIndex(cell[1], rj),
                                                                 lattice.axis(2).controlIndex(cell[2], rk)));
        Eigen::Index row = 0;
        for (int k = 0; k <= n[2]; ++k)
          for (int j = 0; j <= n[1]; ++j)
            for (int i = 0; i <= n[0]; ++i, ++row)
              volume.points.row(row) += extraction[0](ri, i) * extraction[1](rj, j) * extraction[2](rk, k) * point;
      }
  Eigen::Affine3d toLocalParameter = Eigen::Affine3d::Identity();
  toLocalParameter.linear() = lattice.restAffineLinear().inverse();
  toLocalParameter.translation() = -(toLocalParameter.linear() * lattice.restAffineOffset());
  volume.toParameter = toCell * toLocalParameter * lattice.frame().inverse();
  return volume;
}

BezierPatch composeBezierPatch(const BernsteinVolume& volume, const BezierPatch& patch) {
  checkPatch(patch);
  const Eigen::Vector3i n = volume.degrees;
  if ((n.array() < 1).any()) throw CadError("a Bernstein volume needs degree >= 1 per axis");
  if (volume.points.rows() != static_cast<Eigen::Index>(n[0] + 1) * (n[1] + 1) * (n[2] + 1))
    throw CadError("a Bernstein volume of degrees (" + std::to_string(n[0]) + ", " + std::to_string(n[1]) + ", " +
                   std::to_string(n[2]) + ") needs (L+1)(M+1)(N+1) points, got " + std::to_string(volume.points.rows()));
  ScaledPoly weight;
  ScaledPoly uh[3];
  homogeneousParameters(volume, patch, weight, uh);
  const std::vector<ScaledPoly> tu = composedBasis(weight, uh[0], n[0]);
  const std::vector<ScaledPoly> tv = composedBasis(weight, uh[1], n[1]);
  const std::vector<ScaledPoly> tw = composedBasis(weight, uh[2], n[2]);

  // Contract the lattice axis by axis: i into G_jk, j into H_k, k into the numerator.
  const int p = patch.degreeU;
  const int q = patch.degreeV;
  ScaledPoly numerator = ScaledPoly::zero(volume.totalDegree() * p, volume.totalDegree() * q, 3);
  Eigen::Index row = 0;
  for (int k = 0; k <= n[2]; ++k) {
    ScaledPoly h = ScaledPoly::zero((n[0] + n[1]) * p, (n[0] + n[1]) * q, 3);
    for (int j = 0; j <= n[1]; ++j) {
      ScaledPoly g = ScaledPoly::zero(n[0] * p, n[0] * q, 3);
      for (int i = 0; i <= n[0]; ++i, ++row) g.c += tu[i].c * volume.points.row(row);
      accumulate(h, multiply(g, tv[j]));
    }
    accumulate(numerator, multiply(h, tw[k]));
  }
  ScaledPoly denominator = ScaledPoly::constant(1.0);
  for (int power = 0; power < volume.totalDegree(); ++power) denominator = multiply(denominator, weight);

  BezierPatch out;
  out.degreeU = numerator.du;
  out.degreeV = numerator.dv;
  out.poles.resize(out.poleCount(), 3);
  const bool rational = patch.weights.size() > 0;
  if (rational) out.weights.resize(out.poleCount());
  for (int b = 0; b <= out.degreeV; ++b)
    for (int a = 0; a <= out.degreeU; ++a) {
      const Eigen::Index at = a + (out.degreeU + 1) * b;
      const double w = denominator.c(at, 0);
      out.poles.row(at) = numerator.c.row(at) / w;
      if (rational) out.weights[at] = w / (binomial(out.degreeU, a) * binomial(out.degreeV, b));
    }
  return out;
}

}  // namespace ffdkit::cad
