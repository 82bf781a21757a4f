#include "ffdkit/geometry/curvenet/multisided_patch.h"

#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

namespace ffdkit::geometry::curvenet {
namespace {

// C^(v) = mean_k K_k(t_k + dir_k v) - X: the transversal (rule (a) average for >= 2 members).
VectorJet transversal(const CurveNetwork& net, const Transversal& tr, const Jet& v) {
  VectorJet sum;
  const double weight = 1.0 / static_cast<double>(tr.members.size());
  for (std::size_t k = 0; k < tr.members.size(); ++k) {
    const NetworkCurve& curve = net.curves[tr.members[k].curve];
    const double dir = tr.directions[k];
    const Jet t = tr.members[k].parameter + dir * v;
    sum = sum + weight * compose(curve.evaluate(t.v), curve.evaluate(t.v, 1), curve.evaluate(t.v, 2), t);
  }
  sum.v -= net.vertices[tr.vertex].position;
  return sum;
}

// Row vector times matrix, derivative by derivative: (p^T c)_k = sum_j p_j c_jk.
VectorJet transform(const Eigen::Matrix3d& c, const VectorJet& p) {
  const Eigen::Matrix3d ct = c.transpose();
  return {ct * p.v, ct * p.x, ct * p.y, ct * p.xx, ct * p.xy, ct * p.yy};
}

}  // namespace

VectorJet runSweep(const CurveNetwork& net, int runId, const Jet& ut, const Jet& v) {
  const Run& run = net.runs[runId];
  const NetworkCurve& guide = net.curves[run.curve];
  const Jet t = run.tStart + run.delta() * ut;
  const VectorJet c = compose(guide.evaluate(t.v), guide.evaluate(t.v, 1), guide.evaluate(t.v, 2), t);
  // g of sec. 5.2.1 with the influence weights of the physical transversal curves.
  // A free end has no transversal: the single sweep of the other end (rule (c), sec. 5.2.4).
  if (run.atStart.members.empty()) return transversal(net, run.atEnd, v) + c;
  if (run.atEnd.members.empty()) return transversal(net, run.atStart, v) + c;
  if (run.affine) {
    // S = C^-(v) M^-(u) + C^+(v) M^+(u) + C(u), row vectors (sec. 5.2.1).
    const VectorJet a = transversal(net, run.atStart, v), b = transversal(net, run.atEnd, v);
    const Jet q = (run.delta() * run.delta()) * (ut * ut - ut);
    return (1.0 - ut) * a + ut * b + c + q * transform(run.cStart, a) + q * transform(run.cEnd, b);
  }
  const double wm = run.atStart.influence, wp = run.atEnd.influence;
  const Jet denom = wm * (1.0 - ut) + wp * ut;
  const Jet gm = (wm * (1.0 - ut)) / denom;
  const Jet gp = (wp * ut) / denom;
  return gm * transversal(net, run.atStart, v) + gp * transversal(net, run.atEnd, v) + c;
}

VectorJet evaluatePatch(const CurveNetwork& net, int faceId, const NGonDomain& domain,
                        const Eigen::Vector2d& p, const PatchOptions& options) {
  const Face& face = net.faces.at(faceId);
  const int n = static_cast<int>(face.sides.size());
  if (domain.sides() != n) {
    throw std::invalid_argument("patch of face " + std::to_string(faceId) + " has " +
                                std::to_string(n) + " sides, got a domain with " +
                                std::to_string(domain.sides()));
  }
  if (options.blendingExponent < 1) {
    throw std::invalid_argument("blending exponent must be >= 1, got " +
                                std::to_string(options.blendingExponent));
  }
  const int corner = domain.vertexAt(p);
  if (corner >= 0) {
    VectorJet q;
    const FaceSide& s = face.sides[corner];
    if (s.startVertex >= 0) {
      q.v = net.vertices[s.startVertex].position;
    } else {
      const Run& run = net.runs[s.run];
      q.v = net.curves[run.curve].evaluate(run.tStart + run.delta() * (s.forward ? s.rho0 : s.rho1));
    }
    return q;
  }
  const std::vector<Jet> b = domain.barycentric(p);
  std::vector<Jet> blend = domain.blend(b, options.blendingExponent);
  if (face.openRegion) {
    // Rule (c), sec. 5.2.4: the virtual side's weight goes to the first and the last real
    // side, split by u~ of the virtual side, so the real weights still sum to 1.
    const Jet ut = domain.uTilde(n - 1, b);
    blend[0] = blend[0] + ut * blend[n - 1];
    blend[n - 2] = blend[n - 2] + (1.0 - ut) * blend[n - 1];
    blend[n - 1] = Jet::constant(0.0);
  }
  VectorJet q;
  for (int i = 0; i < n; ++i) {
    if (blend[i].v == 0.0 && blend[i].x == 0.0 && blend[i].y == 0.0 && blend[i].xx == 0.0 &&
        blend[i].xy == 0.0 && blend[i].yy == 0.0) {
      continue;
    }
    const FaceSide& side = face.sides[i];
    if (side.run < 0) continue;
    const double dPrev = face.sides[(i - 1 + n) % n].delta;
    const double dNext = face.sides[(i + 1) % n].delta;
    const Jet ut = domain.uTilde(i, b);
    const Jet d = domain.distance(i, b);
    // Open region: the single sweeps next to the virtual side take F = Delta of their one
    // transversal side (Kuriyama 1996, sec. 5.2.4 c).
    Jet f = dPrev * (1.0 - ut) + dNext * ut;
    if (face.openRegion && i == 0) f = Jet::constant(dNext);
    if (face.openRegion && i == n - 2) f = Jet::constant(dPrev);
    const Jet v = f * d;
    const double span = side.rho1 - side.rho0;
    const Jet utRun = side.forward ? side.rho0 + span * ut : side.rho1 - span * ut;
    const VectorJet s = runSweep(net, side.run, utRun, side.forward ? v : -v);
    q = q + blend[i] * s;
  }
  return q;
}

Eigen::Vector3d patchNormal(const VectorJet& q) {
  const Eigen::Vector3d n = q.x.cross(q.y);
  const double len = n.norm();
  return len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

}  // namespace ffdkit::geometry::curvenet
