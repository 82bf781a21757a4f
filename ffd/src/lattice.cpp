#include "ffdkit/ffd/lattice.h"

#include <atomic>
#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/LU>

namespace ffdkit::ffd {
namespace {

std::uint64_t nextRevision() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

std::string str(const Eigen::Vector3i& v) {
  std::ostringstream os;
  os << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
  return os.str();
}

void checkCounts(const Eigen::Vector3i& counts) {
  if ((counts.array() < 2).any()) {
    throw LatticeError("lattice needs >= 2 points per axis, got " + str(counts));
  }
  if (counts.cast<double>().prod() > static_cast<double>(kMaxLatticeControlPoints)) {
    throw LatticeError("lattice has too many control points: " + str(counts) + ", more than " +
                       std::to_string(kMaxLatticeControlPoints));
  }
}

void checkFinite(const Eigen::Ref<const Eigen::MatrixX3d>& points, const char* what) {
  for (Eigen::Index r = 0; r < points.rows(); ++r) {
    if (!points.row(r).allFinite()) {
      std::ostringstream os;
      os << what << ": point " << r << " is not finite (" << points(r, 0) << ", " << points(r, 1) << ", "
         << points(r, 2) << ")";
      throw LatticeError(os.str());
    }
  }
}

void checkFrame(const Eigen::Affine3d& frame) {
  if (!frame.matrix().allFinite()) throw LatticeError("lattice frame is not finite");
  const double det = frame.linear().determinant();
  const double scale = frame.linear().norm();
  if (!(std::abs(det) > 1e-12 * scale * scale * scale)) {
    throw LatticeError("lattice frame is singular (determinant " + std::to_string(det) + ")");
  }
}

const char* kAxisNames[3] = {"lattice axis u", "lattice axis v", "lattice axis w"};

}  // namespace

Lattice::Lattice(const Eigen::Vector3i& counts, const std::array<AxisBasis, 3>& bases,
                 const Eigen::Ref<const Eigen::MatrixX3d>& restPoints, const Eigen::Affine3d& frame)
    : counts_(counts) {
  checkCounts(counts);
  for (int a = 0; a < 3; ++a) axes_[a] = AxisSpline(bases[a], counts[a], kAxisNames[a]);
  checkFrame(frame);
  frame_ = frame;
  setRestInternal(restPoints);
  revision_ = nextRevision();
  restRevision_ = nextRevision();
}

Eigen::Vector3i Lattice::gridIndex(Eigen::Index flat) const {
  if (flat < 0 || flat >= pointCount()) {
    throw LatticeError("lattice point index " + std::to_string(flat) + " out of range [0, " +
                       std::to_string(pointCount()) + ")");
  }
  const Eigen::Index l = counts_[0];
  const Eigen::Index m = counts_[1];
  return Eigen::Vector3i(static_cast<int>(flat % l), static_cast<int>((flat / l) % m),
                         static_cast<int>(flat / (l * m)));
}

Eigen::Vector3d Lattice::parameterMin() const {
  return {axes_[0].domainMin(), axes_[1].domainMin(), axes_[2].domainMin()};
}

Eigen::Vector3d Lattice::parameterMax() const {
  return {axes_[0].domainMax(), axes_[1].domainMax(), axes_[2].domainMax()};
}

void Lattice::setControlPoints(const Eigen::Ref<const Eigen::MatrixX3d>& points) {
  if (points.rows() != pointCount()) {
    throw LatticeError("setControlPoints: expected " + std::to_string(pointCount()) + " x 3 points for a " +
                       str(counts_) + " lattice, got " + std::to_string(points.rows()) + " x 3");
  }
  checkFinite(points, "setControlPoints");
  control_ = points;
  revision_ = nextRevision();
}

void Lattice::setControlPoint(Eigen::Index flat, const Eigen::Vector3d& p) {
  gridIndex(flat);  // range check
  if (!p.allFinite()) {
    throw LatticeError("setControlPoint: point " + std::to_string(flat) + " is not finite");
  }
  control_.row(flat) = p.transpose();
  revision_ = nextRevision();
}

void Lattice::resetToRest() {
  control_ = rest_;
  weights_ = restWeights_;
  revision_ = nextRevision();
}

Eigen::VectorXd Lattice::checkedWeights(const Eigen::Ref<const Eigen::VectorXd>& weights, const char* what) const {
  if (weights.size() != pointCount()) {
    throw LatticeError(std::string(what) + ": expected " + std::to_string(pointCount()) + " weights for a " +
                       str(counts_) + " lattice, got " + std::to_string(weights.size()));
  }
  bool unit = true;
  for (Eigen::Index f = 0; f < weights.size(); ++f) {
    if (!(std::isfinite(weights[f]) && weights[f] > 0.0)) {
      std::ostringstream os;
      os << what << ": weight " << f << " must be finite and > 0, got " << weights[f];
      throw LatticeError(os.str());
    }
    unit = unit && weights[f] == 1.0;
  }
  // All weights 1 is stored as none: the polynomial lattice and its code path.
  return unit ? Eigen::VectorXd() : Eigen::VectorXd(weights);
}

Eigen::VectorXd Lattice::weights() const {
  return weights_.size() > 0 ? weights_ : Eigen::VectorXd::Ones(pointCount());
}

double Lattice::weight(Eigen::Index flat) const {
  gridIndex(flat);  // range check
  return weights_.size() > 0 ? weights_[flat] : 1.0;
}

Eigen::VectorXd Lattice::restWeights() const {
  return restWeights_.size() > 0 ? restWeights_ : Eigen::VectorXd::Ones(pointCount());
}

void Lattice::setWeights(const Eigen::Ref<const Eigen::VectorXd>& weights) {
  weights_ = checkedWeights(weights, "setWeights");
  revision_ = nextRevision();
}

void Lattice::setWeight(Eigen::Index flat, double weight) {
  gridIndex(flat);  // range check
  if (!(std::isfinite(weight) && weight > 0.0)) {
    std::ostringstream os;
    os << "setWeight: weight " << flat << " must be finite and > 0, got " << weight;
    throw LatticeError(os.str());
  }
  Eigen::VectorXd w = weights();
  w[flat] = weight;
  weights_ = checkedWeights(w, "setWeight");
  revision_ = nextRevision();
}

void Lattice::setRestWeights(const Eigen::Ref<const Eigen::VectorXd>& weights) {
  Eigen::VectorXd checked = checkedWeights(weights, "setRestWeights");
  const Eigen::VectorXd previous = restWeights_;
  const Eigen::MatrixX3d control = control_;
  restWeights_ = checked;
  try {
    setRestInternal(Eigen::MatrixX3d(rest_));  // the affine test and the degeneracy check see the weights
  } catch (...) {
    restWeights_ = previous;
    control_ = control;
    throw;
  }
  control_ = control;
  weights_ = restWeights_;
  revision_ = nextRevision();
  restRevision_ = nextRevision();
}

void Lattice::setRestPoints(const Eigen::Ref<const Eigen::MatrixX3d>& restPoints) {
  setRestInternal(restPoints);
  weights_ = restWeights_;
  cylinder_.reset();
  revision_ = nextRevision();
  restRevision_ = nextRevision();
}

void Lattice::setFrame(const Eigen::Affine3d& frame) {
  checkFrame(frame);
  frame_ = frame;
  restRevision_ = nextRevision();
}

void Lattice::setOutsidePolicy(const OutsidePolicy& policy) {
  if (policy.kind == OutsidePolicy::Kind::Falloff && !(policy.distance > 0.0 && std::isfinite(policy.distance))) {
    throw LatticeError("Falloff outside policy needs a finite distance > 0, got " + std::to_string(policy.distance));
  }
  policy_ = policy;
  restRevision_ = nextRevision();
}

void Lattice::setRestInternal(const Eigen::Ref<const Eigen::MatrixX3d>& restPoints) {
  if (restPoints.rows() != pointCount()) {
    throw LatticeError("rest lattice: expected " + std::to_string(pointCount()) + " x 3 points for a " +
                       str(counts_) + " lattice, got " + std::to_string(restPoints.rows()) + " x 3");
  }
  checkFinite(restPoints, "rest lattice");
  const double size = (restPoints.colwise().maxCoeff() - restPoints.colwise().minCoeff()).norm();
  if (!(size > 0.0)) throw LatticeError("rest lattice is degenerate: all points coincide");

  // Affine rest map? Fit Pbar_ijk ~ A (g_i, g_j, g_k) + b; B-splines reproduce linear functions at
  // the Greville abscissae, so an exact fit means Xbar(u) = A u + b everywhere.
  bool affine = !(axes_[0].periodic() || axes_[1].periodic() || axes_[2].periodic()) && restWeights_.size() == 0;
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  if (affine) {
    const Eigen::Index n = pointCount();
    Eigen::MatrixXd G(n, 4);
    for (Eigen::Index f = 0; f < n; ++f) {
      const Eigen::Vector3i g = gridIndex(f);
      G.row(f) << axes_[0].greville()[g[0]], axes_[1].greville()[g[1]], axes_[2].greville()[g[2]], 1.0;
    }
    const Eigen::Matrix<double, 4, 3> X = (G.transpose() * G).ldlt().solve(G.transpose() * restPoints);
    const double residual = (G * X - restPoints).cwiseAbs().maxCoeff();
    A = X.topRows<3>().transpose();
    b = X.row(3).transpose();
    affine = residual <= 1e-13 * size;
  }
  rest_ = restPoints;
  control_ = restPoints;
  restAffine_ = affine;
  restA_ = A;
  restB_ = b;
  restSize_ = size;

  // Zero volume: |det dXbar/duvw| negligible at the box centre and at every cell centre.
  double maxDet = 0.0;
  Eigen::Vector3d uvw;
  const Eigen::Vector3d lo = parameterMin();
  const Eigen::Vector3d hi = parameterMax();
  const Eigen::Vector3d range = hi - lo;
  const double scale = size * size * size / (range.prod());
  for (int ci = 0; ci < axes_[0].cellCount(); ++ci) {
    for (int cj = 0; cj < axes_[1].cellCount(); ++cj) {
      for (int ck = 0; ck < axes_[2].cellCount(); ++ck) {
        uvw << 0.5 * (axes_[0].cellMin(ci) + axes_[0].cellMax(ci)), 0.5 * (axes_[1].cellMin(cj) + axes_[1].cellMax(cj)),
            0.5 * (axes_[2].cellMin(ck) + axes_[2].cellMax(ck));
        maxDet = std::max(maxDet, std::abs(restJacobian(uvw).determinant()));
        if (maxDet > 1e-10 * scale) break;
      }
    }
  }
  if (!(maxDet > 1e-10 * scale)) {
    throw LatticeError("rest lattice is degenerate (zero volume): |det dXbar/d(u,v,w)| <= " +
                       std::to_string(maxDet) + " for a lattice of size " + std::to_string(size));
  }
}

Eigen::Vector3d Lattice::evaluateOn(const Eigen::MatrixX3d& points, const Eigen::VectorXd& weights,
                                    const Eigen::Vector3d& uvw, Eigen::Matrix3d* jac) const {
  constexpr int kMax = 33;
  double N[3][kMax];
  double D[3][kMax];
  int cell[3];
  for (int a = 0; a < 3; ++a) {
    cell[a] = axes_[a].cellOf(uvw[a]);
    axes_[a].basis(cell[a], uvw[a], N[a], jac ? D[a] : nullptr);
  }
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  const int pu = axes_[0].degree();
  const int pv = axes_[1].degree();
  const int pw = axes_[2].degree();
  if (weights.size() > 0) {
    // Homogeneous sums (Lamousin & Waggenspack 1994): N = sum B w P, W = sum B w, X = N / W,
    // dX = (dN - X dW^T) / W.
    Eigen::Vector3d dW = Eigen::Vector3d::Zero();
    double W = 0.0;
    for (int c = 0; c <= pw; ++c) {
      const int k = axes_[2].controlIndex(cell[2], c);
      for (int b = 0; b <= pv; ++b) {
        const int j = axes_[1].controlIndex(cell[1], b);
        for (int a = 0; a <= pu; ++a) {
          const Eigen::Index f = index(axes_[0].controlIndex(cell[0], a), j, k);
          const double w = weights[f];
          const Eigen::Vector3d p = w * points.row(f).transpose();
          const double n = N[0][a] * N[1][b] * N[2][c];
          x += n * p;
          W += n * w;
          if (jac) {
            const Eigen::Vector3d d(D[0][a] * N[1][b] * N[2][c], N[0][a] * D[1][b] * N[2][c], N[0][a] * N[1][b] * D[2][c]);
            J += p * d.transpose();
            dW += w * d;
          }
        }
      }
    }
    x /= W;
    if (jac) *jac = (J - x * dW.transpose()) / W;
    return x;
  }
  for (int c = 0; c <= pw; ++c) {
    const int k = axes_[2].controlIndex(cell[2], c);
    for (int b = 0; b <= pv; ++b) {
      const int j = axes_[1].controlIndex(cell[1], b);
      for (int a = 0; a <= pu; ++a) {
        const int i = axes_[0].controlIndex(cell[0], a);
        const Eigen::Vector3d p = points.row(index(i, j, k)).transpose();
        x += (N[0][a] * N[1][b] * N[2][c]) * p;
        if (jac) {
          J.col(0) += (D[0][a] * N[1][b] * N[2][c]) * p;
          J.col(1) += (N[0][a] * D[1][b] * N[2][c]) * p;
          J.col(2) += (N[0][a] * N[1][b] * D[2][c]) * p;
        }
      }
    }
  }
  if (jac) *jac = J;
  return x;
}

Eigen::Vector3d Lattice::evaluate(const Eigen::Vector3d& uvw) const {
  return evaluateOn(control_, weights_, uvw, nullptr);
}

Eigen::Vector3d Lattice::evaluateRest(const Eigen::Vector3d& uvw) const {
  return evaluateOn(rest_, restWeights_, uvw, nullptr);
}

Eigen::Matrix3d Lattice::jacobian(const Eigen::Vector3d& uvw, Eigen::Vector3d* value) const {
  Eigen::Matrix3d J;
  const Eigen::Vector3d x = evaluateOn(control_, weights_, uvw, &J);
  if (value) *value = x;
  return J;
}

Eigen::Matrix3d Lattice::restJacobian(const Eigen::Vector3d& uvw, Eigen::Vector3d* value) const {
  Eigen::Matrix3d J;
  const Eigen::Vector3d x = evaluateOn(rest_, restWeights_, uvw, &J);
  if (value) *value = x;
  return J;
}

Lattice makeBoxLattice(const BoxLatticeOptions& options) {
  checkCounts(options.counts);
  if (!options.boxMin.allFinite() || !options.boxMax.allFinite() ||
      !(options.boxMax.array() > options.boxMin.array()).all()) {
    std::ostringstream os;
    os << "box lattice needs finite boxMax > boxMin per axis, got min (" << options.boxMin.transpose()
       << ") max (" << options.boxMax.transpose() << ")";
    throw LatticeError(os.str());
  }
  std::array<AxisBasis, 3> bases = options.bases;
  std::array<AxisSpline, 3> axes;
  for (int a = 0; a < 3; ++a) {
    if (bases[a].kind == AxisBasis::Kind::PeriodicBSpline) {
      throw LatticeError(std::string(kAxisNames[a]) + ": a box lattice cannot have a periodic axis");
    }
    if (options.capDegreeToCount && bases[a].kind == AxisBasis::Kind::BSpline && bases[a].knots.size() == 0 &&
        bases[a].degree > options.counts[a] - 1) {
      bases[a].degree = options.counts[a] - 1;
    }
    axes[a] = AxisSpline(bases[a], options.counts[a], kAxisNames[a]);
  }
  const Eigen::Index n = options.counts.prod();
  Eigen::MatrixX3d rest(n, 3);
  const Eigen::Index l = options.counts[0];
  const Eigen::Index m = options.counts[1];
  for (Eigen::Index f = 0; f < n; ++f) {
    const Eigen::Index g[3] = {f % l, (f / l) % m, f / (l * m)};
    for (int a = 0; a < 3; ++a) {
      const double t = (axes[a].greville()[g[a]] - axes[a].domainMin()) / (axes[a].domainMax() - axes[a].domainMin());
      rest(f, a) = options.boxMin[a] + (options.boxMax[a] - options.boxMin[a]) * t;
    }
  }
  Lattice lattice(options.counts, bases, rest, options.frame);
  lattice.setOutsidePolicy(options.outsidePolicy);
  return lattice;
}

Lattice makeLattice(const Eigen::Vector3i& counts, const std::array<AxisBasis, 3>& bases,
                    const Eigen::Ref<const Eigen::MatrixX3d>& restPoints, const Eigen::Affine3d& frame) {
  return Lattice(counts, bases, restPoints, frame);
}

}  // namespace ffdkit::ffd
