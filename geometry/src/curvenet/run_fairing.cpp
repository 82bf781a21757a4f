#include "ffdkit/geometry/curvenet/run_fairing.h"

#include <stdexcept>
#include <string>

#include <Eigen/Dense>

#include "ffdkit/geometry/gauss_legendre.h"

namespace ffdkit::geometry::curvenet {
namespace {

// One side of a run in the energy: the transversals run at sign * Delta-+ * v, v in [0, 1].
struct EnergySide {
  int sign = 1;
  double deltaStart = 0.0, deltaEnd = 0.0;
};

// Value, d/dv and d2/dv2 of v -> C^(sign * delta * v) (rule (a) average included).
void transversalJet(const CurveNetwork& net, const Transversal& tr, double scale, double v,
                    Eigen::Vector3d& c0, Eigen::Vector3d& c1, Eigen::Vector3d& c2) {
  c0.setZero();
  c1.setZero();
  c2.setZero();
  const double w = 1.0 / static_cast<double>(tr.members.size());
  for (std::size_t k = 0; k < tr.members.size(); ++k) {
    const NetworkCurve& curve = net.curves[tr.members[k].curve];
    const double dir = tr.directions[k] * scale;
    const double t = tr.members[k].parameter + dir * v;
    c0 += w * curve.evaluate(t);
    c1 += w * dir * curve.evaluate(t, 1);
    c2 += w * dir * dir * curve.evaluate(t, 2);
  }
  c0 -= net.vertices[tr.vertex].position;
}

std::vector<EnergySide> energySides(const CurveNetwork& net, int r) {
  std::vector<EnergySide> out;
  for (int sign : {1, -1}) {
    EnergySide side;
    side.sign = sign;
    bool haveStart = false, haveEnd = false;
    for (const Face& f : net.faces) {
      const int n = static_cast<int>(f.sides.size());
      for (int i = 0; i < n; ++i) {
        const FaceSide& s = f.sides[i];
        if (s.run != r || s.forward != (sign > 0)) continue;
        const FaceSide& prev = f.sides[(i - 1 + n) % n];
        const FaceSide& next = f.sides[(i + 1) % n];
        // Forward sides start at the run start; backward sides start at the run end.
        if (sign > 0 && s.rho0 == 0.0 && prev.delta > 0.0) { side.deltaStart = prev.delta; haveStart = true; }
        if (sign > 0 && s.rho1 == 1.0 && next.delta > 0.0) { side.deltaEnd = next.delta; haveEnd = true; }
        if (sign < 0 && s.rho1 == 1.0 && prev.delta > 0.0) { side.deltaEnd = prev.delta; haveEnd = true; }
        if (sign < 0 && s.rho0 == 0.0 && next.delta > 0.0) { side.deltaStart = next.delta; haveStart = true; }
      }
    }
    if (haveStart && haveEnd) out.push_back(side);
  }
  return out;
}

// Accumulates A (6 x 6) and r (6 x 3) of <psi_a, psi_b>, <psi_a, R^(k)> and the energy of R.
void assemble(const CurveNetwork& net, const curvenet::Run& run, const EnergySide& side,
              const GaussLegendreRule& rule, Eigen::Matrix<double, 6, 6>& a,
              Eigen::Matrix<double, 6, 3>& r, double& rr) {
  const double d = run.delta();
  const NetworkCurve& guide = net.curves[run.curve];
  for (Eigen::Index iu = 0; iu < rule.nodes.size(); ++iu) {
    const double u = 0.5 * (rule.nodes[iu] + 1.0), wu = 0.5 * rule.weights[iu];
    const Eigen::Vector3d guideUU = d * d * guide.evaluate(run.tStart + d * u, 2);
    for (Eigen::Index iv = 0; iv < rule.nodes.size(); ++iv) {
      const double v = 0.5 * (rule.nodes[iv] + 1.0), w = wu * 0.5 * rule.weights[iv];
      Eigen::Vector3d m0, m1, m2, p0, p1, p2;
      transversalJet(net, run.atStart, side.sign * side.deltaStart, v, m0, m1, m2);
      transversalJet(net, run.atEnd, side.sign * side.deltaEnd, v, p0, p1, p2);
      // psi_{-+,j}: uu, uv, vv derivatives (Kuriyama 1996, sec. 5.2.1 explicit system).
      Eigen::Matrix<double, 6, 3> psi;  // rows a, columns (uu, uv, vv)
      for (int j = 0; j < 3; ++j) {
        psi.row(j) << 2 * d * d * m0[j], d * d * (2 * u - 1) * m1[j], d * d * (u * u - u) * m2[j];
        psi.row(3 + j) << 2 * d * d * p0[j], d * d * (2 * u - 1) * p1[j], d * d * (u * u - u) * p2[j];
      }
      const Eigen::Vector3d ruu = guideUU, ruv = p1 - m1, rvv = (1 - u) * m2 + u * p2;
      const Eigen::Vector3d metric(1.0, 2.0, 1.0);
      a += w * psi * metric.asDiagonal() * psi.transpose();
      Eigen::Matrix3d rk;  // rows (uu, uv, vv), columns k
      rk.row(0) = ruu.transpose();
      rk.row(1) = ruv.transpose();
      rk.row(2) = rvv.transpose();
      r += w * psi * metric.asDiagonal() * rk;
      rr += w * (ruu.squaredNorm() + 2 * ruv.squaredNorm() + rvv.squaredNorm());
    }
  }
}

double energyOf(const Eigen::Matrix<double, 6, 6>& a, const Eigen::Matrix<double, 6, 3>& r, double rr,
                const Eigen::Matrix3d& cStart, const Eigen::Matrix3d& cEnd) {
  double e = rr;
  for (int k = 0; k < 3; ++k) {
    Eigen::Matrix<double, 6, 1> x;
    x << cStart.col(k), cEnd.col(k);
    e += x.dot(a * x) + 2 * x.dot(r.col(k));
  }
  return e;
}

GaussLegendreRule checkedRule(const FairingOptions& options) {
  if (options.quadraturePoints < 4) {
    throw std::invalid_argument("fairing needs >= 4 quadrature points, got " +
                                std::to_string(options.quadraturePoints));
  }
  return gaussLegendreRule(options.quadraturePoints);
}

}  // namespace

double runFairingEnergy(const CurveNetwork& net, int r, const Eigen::Matrix3d& cStart,
                        const Eigen::Matrix3d& cEnd, const FairingOptions& options) {
  const GaussLegendreRule rule = checkedRule(options);
  const curvenet::Run& run = net.runs.at(r);
  Eigen::Matrix<double, 6, 6> a = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 3> rhs = Eigen::Matrix<double, 6, 3>::Zero();
  double rr = 0.0;
  if (run.atStart.members.empty() || run.atEnd.members.empty()) return 0.0;
  for (const EnergySide& side : energySides(net, r)) assemble(net, run, side, rule, a, rhs, rr);
  return energyOf(a, rhs, rr, cStart, cEnd);
}

FairingResult fairRunSweeps(CurveNetwork& net, const FairingOptions& options) {
  const GaussLegendreRule rule = checkedRule(options);
  FairingResult result;
  for (int r = 0; r < static_cast<int>(net.runs.size()); ++r) {
    curvenet::Run& run = net.runs[r];
    if (run.atStart.members.empty() || run.atEnd.members.empty()) continue;
    const std::vector<EnergySide> sides = energySides(net, r);
    if (sides.empty()) continue;
    Eigen::Matrix<double, 6, 6> a = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 3> rhs = Eigen::Matrix<double, 6, 3>::Zero();
    double rr = 0.0;
    for (const EnergySide& side : sides) assemble(net, run, side, rule, a, rhs, rr);
    const Eigen::Matrix<double, 6, 3> x = a.completeOrthogonalDecomposition().solve(-rhs);
    run.cStart = x.topRows<3>();
    run.cEnd = x.bottomRows<3>();
    run.affine = true;
    RunFairing f;
    f.run = r;
    f.sides = static_cast<int>(sides.size());
    f.energyBefore = rr;
    f.energyAfter = energyOf(a, rhs, rr, run.cStart, run.cEnd);
    result.totalBefore += f.energyBefore;
    result.totalAfter += f.energyAfter;
    result.runs.push_back(f);
  }
  return result;
}

}  // namespace ffdkit::geometry::curvenet
