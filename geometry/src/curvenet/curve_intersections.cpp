#include "curve_intersections.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Geometry>

#include "curve_point_search.h"

namespace ffdkit::geometry::curvenet::detail {
namespace {

// The search over every pair of curves; each step reads what the constructor set up.
class CurveIntersector {
 public:
  CurveIntersector(CurveNetwork& network, const CurveSamples& samples, double tolerance, double minimumCrossingAngle)
      : net_(network),
        samples_(samples.points),
        params_(samples.params),
        kSamples(samples.samplesPerSegment),
        nc_(static_cast<int>(network.curves.size())),
        tau_(tolerance),
        minimumAngleDegrees_(minimumCrossingAngle),
        sinMin_(std::sin(minimumCrossingAngle * std::numbers::pi / 180.0)) {}

  std::vector<PairHit> findAll() {
    makeSegmentBoxes();
    std::vector<PairHit> hits;
    for (int a = 0; a < nc_; ++a)
      for (int b = a + 1; b < nc_; ++b) intersect(a, b, hits);
    return hits;
  }

 private:
  // Per-segment sample boxes and the longest sample step of each curve: only segment pairs whose
  // boxes come within the gate are compared.
  void makeSegmentBoxes() {
    step_.assign(nc_, 0.0);
    boxes_.assign(nc_, {});
    for (int c = 0; c < nc_; ++c) {
      const Eigen::MatrixX3d& p = samples_[c];
      const Eigen::Index n = p.rows();
      for (Eigen::Index i = 1; i < n; ++i) step_[c] = std::max(step_[c], (p.row(i) - p.row(i - 1)).norm());
      if (net_.curves[c].closed()) step_[c] = std::max(step_[c], (p.row(0) - p.row(n - 1)).norm());
      const int segs = static_cast<int>(net_.curves[c].segments().size());
      for (int k = 0; k < segs; ++k) {
        Eigen::AlignedBox3d box;
        for (int q = 0; q <= kSamples; ++q) {
          const Eigen::Index idx =
              net_.curves[c].closed() ? (k * kSamples + q) % n : std::min<Eigen::Index>(k * kSamples + q, n - 1);
          box.extend(p.row(idx).transpose());
        }
        boxes_[c].push_back(box);
      }
    }
  }

  // The sample rows of curves a and b worth comparing: the smallest windows holding every
  // segment pair whose boxes come within `gate`. False if none do.
  bool sampleWindows(int a, int b, double gate, Eigen::Index& r0, Eigen::Index& r1, Eigen::Index& c0,
                     Eigen::Index& c1) const {
    r0 = std::numeric_limits<Eigen::Index>::max(), r1 = -1, c0 = r0, c1 = -1;
    for (int ka = 0; ka < static_cast<int>(boxes_[a].size()); ++ka) {
      Eigen::AlignedBox3d grown = boxes_[a][ka];
      grown.min().array() -= gate;
      grown.max().array() += gate;
      for (int kb = 0; kb < static_cast<int>(boxes_[b].size()); ++kb) {
        if (!grown.intersects(boxes_[b][kb])) continue;
        r0 = std::min<Eigen::Index>(r0, ka * kSamples);
        r1 = std::max<Eigen::Index>(r1, (ka + 1) * kSamples);
        c0 = std::min<Eigen::Index>(c0, kb * kSamples);
        c1 = std::max<Eigen::Index>(c1, (kb + 1) * kSamples);
      }
    }
    if (r1 < 0) return false;
    r1 = std::min(r1, samples_[a].rows() - 1);
    c1 = std::min(c1, samples_[b].rows() - 1);
    return true;
  }

  // Where curves a and b meet, appended to `hits`: each local minimum of the sampled distance
  // within the gate, refined to the closest points (and snapped to an open end within tau: a T).
  void intersect(int a, int b, std::vector<PairHit>& hits) {
    const double gate = tau_ + step_[a] + step_[b];
    Eigen::Index r0, r1, c0, c1;
    if (!sampleWindows(a, b, gate, r0, r1, c0, c1)) return;
    // Wrap-around neighbours only when the window is the whole closed curve.
    const bool wrapA = net_.curves[a].closed() && r0 == 0 && r1 == samples_[a].rows() - 1;
    const bool wrapB = net_.curves[b].closed() && c0 == 0 && c1 == samples_[b].rows() - 1;
    const Eigen::MatrixX3d pa = samples_[a].middleRows(r0, r1 - r0 + 1);
    const Eigen::MatrixX3d pb = samples_[b].middleRows(c0, c1 - c0 + 1);
    const Eigen::Index na = pa.rows(), nb = pb.rows();
    Eigen::MatrixXd dist(na, nb);
    for (Eigen::Index i = 0; i < na; ++i) dist.row(i) = (pb.rowwise() - pa.row(i)).rowwise().norm().transpose();
    Eigen::Index mi = 0, mj = 0;
    if (dist.minCoeff(&mi, &mj) > gate) return;
    std::vector<PairHit> pairHits;
    for (Eigen::Index i = 0; i < na; ++i) {
      for (Eigen::Index j = 0; j < nb; ++j) {
        if (dist(i, j) > gate || !isLocalMinimum(dist, i, j, wrapA, wrapB)) continue;
        double s = params_[a][r0 + i], t = params_[b][c0 + j];
        refineClosestPoints(net_.curves[a], net_.curves[b], s, t);
        // T-detection (Kuriyama 1996, sec. 5.3.3): an open end within tau of the other curve is
        // the cut point.
        if (snapToEnd(net_.curves[a], s, tau_)) refineOnOneCurve(net_.curves[a].evaluate(s), net_.curves[b], t);
        if (snapToEnd(net_.curves[b], t, tau_)) refineOnOneCurve(net_.curves[b].evaluate(t), net_.curves[a], s);
        const Eigen::Vector3d xa = net_.curves[a].evaluate(s), xb = net_.curves[b].evaluate(t);
        const double d = (xa - xb).norm();
        if (d >= tau_) continue;
        keepClosest(pairHits, PairHit{a, b, s, t, d, 0.5 * (xa + xb)});
      }
    }
    if (pairHits.empty()) noteNearMiss(a, b, params_[a][r0 + mi], params_[b][c0 + mj]);
    for (const PairHit& hit : pairHits) {
      requireCrossingAngle(hit);
      hits.push_back(hit);
    }
  }

  // Whether dist(i, j) is a local minimum over its 8 neighbours (wrapping on closed curves); ties
  // broken by index so a flat valley yields one start, not many.
  static bool isLocalMinimum(const Eigen::MatrixXd& dist, Eigen::Index i, Eigen::Index j, bool wrapA, bool wrapB) {
    const Eigen::Index na = dist.rows(), nb = dist.cols();
    const double dij = dist(i, j);
    for (int di = -1; di <= 1; ++di) {
      for (int dj = -1; dj <= 1; ++dj) {
        if (di == 0 && dj == 0) continue;
        Eigen::Index ii = i + di, jj = j + dj;
        if (wrapA) ii = (ii + na) % na;
        if (wrapB) jj = (jj + nb) % nb;
        if (ii < 0 || ii >= na || jj < 0 || jj >= nb) continue;
        if (dist(ii, jj) < dij || (dist(ii, jj) == dij && (ii * nb + jj) < (i * nb + j))) return false;
      }
    }
    return true;
  }

  // Adds `hit` unless a kept hit lies within tau; then the closer of the two is kept.
  void keepClosest(std::vector<PairHit>& pairHits, const PairHit& hit) const {
    bool duplicate = false;
    for (PairHit& other : pairHits) {
      if ((other.point - hit.point).norm() < tau_) {
        duplicate = true;
        if (hit.distance < other.distance) other = hit;
      }
    }
    if (!duplicate) pairHits.push_back(hit);
  }

  // A near miss is the usual symptom of a crossing the designer meant: say where.
  void noteNearMiss(int a, int b, double s, double t) {
    refineClosestPoints(net_.curves[a], net_.curves[b], s, t);
    const Eigen::Vector3d xa = net_.curves[a].evaluate(s), xb = net_.curves[b].evaluate(t);
    const double d = (xa - xb).norm();
    if (!(d < 3.0 * tau_)) return;
    std::ostringstream msg;
    msg << curveLabel(net_, a) << " and " << curveLabel(net_, b) << " pass within " << d << " of each other near "
        << formatPoint(0.5 * (xa + xb)) << " without meeting (tolerance " << tau_
        << "); raise the tolerance or move them if they should cross";
    net_.notes.push_back(msg.str());
  }

  void requireCrossingAngle(const PairHit& hit) const {
    const Eigen::Vector3d ta = net_.curves[hit.a].evaluate(hit.ta, 1).normalized();
    const Eigen::Vector3d tb = net_.curves[hit.b].evaluate(hit.tb, 1).normalized();
    const double sine = ta.cross(tb).norm();
    if (!(sine < sinMin_)) return;
    std::ostringstream msg;
    msg << curveLabel(net_, hit.a) << " and " << curveLabel(net_, hit.b) << " are tangent or nearly coincident near "
        << formatPoint(hit.point) << " (t = " << hit.ta << " and " << hit.tb << "): crossing angle "
        << std::asin(std::min(1.0, sine)) * 180.0 / std::numbers::pi << " deg, expected >= "
        << minimumAngleDegrees_ << " deg; separate the curves or make them cross";
    throw CurveNetworkError(msg.str());
  }

  CurveNetwork& net_;
  const std::vector<Eigen::MatrixX3d>& samples_;
  const std::vector<Eigen::VectorXd>& params_;
  const int kSamples;  // samples per curve segment
  const int nc_;       // curves
  const double tau_;   // intersection tolerance
  const double minimumAngleDegrees_;
  const double sinMin_;  // sine of the least crossing angle
  std::vector<double> step_;                             // per curve, the longest sample step
  std::vector<std::vector<Eigen::AlignedBox3d>> boxes_;  // per curve, per segment
};

}  // namespace

std::vector<PairHit> findCurveIntersections(CurveNetwork& network, const CurveSamples& samples, double tolerance,
                                            double minimumCrossingAngleDegrees) {
  return CurveIntersector(network, samples, tolerance, minimumCrossingAngleDegrees).findAll();
}

}  // namespace ffdkit::geometry::curvenet::detail
