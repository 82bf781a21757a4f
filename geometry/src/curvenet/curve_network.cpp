#include "ffdkit/geometry/curvenet/curve_network.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <numbers>
#include <numeric>
#include <sstream>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "curve_point_search.h"

namespace ffdkit::geometry::curvenet {
namespace {

using namespace detail;

std::string fmt(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s.precision(6);
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

struct PairHit {
  int a = -1, b = -1;
  double ta = 0.0, tb = 0.0, distance = 0.0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

struct NearMiss {
  double distance = std::numeric_limits<double>::infinity();
  int other = -1;
  double tSelf = 0.0, tOther = 0.0;  ///< sampled start, refined only for the report
};

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); }
  void unite(int a, int b) { parent[find(a)] = find(b); }
};

}  // namespace

int CurveNetwork::edgeCount() const {
  int count = 0;
  for (const HalfEdge& h : halfEdges) count += (h.sign > 0 && !h.dangling) ? 1 : 0;
  return count;
}

std::string curveLabel(const CurveNetwork& network, int curve) {
  std::ostringstream s;
  if (curve >= 0 && curve < static_cast<int>(network.curveNames.size()) &&
      !network.curveNames[curve].empty()) {
    s << "curve '" << network.curveNames[curve] << "' (#" << curve << ")";
  } else {
    s << "curve #" << curve;
  }
  return s.str();
}

CurveNetwork buildCurveNetwork(const CurveNetworkDescription& description,
                               const CurveNetworkOptions& options) {
  CurveNetwork net;
  const int nc = static_cast<int>(description.curves.size());
  if (nc < 2) {
    throw CurveNetworkError("a curve network needs >= 2 curves, got " + std::to_string(nc));
  }
  // --- curves -------------------------------------------------------------------------------
  for (int c = 0; c < nc; ++c) {
    const CurveDescription& d = description.curves[c];
    net.curveNames.push_back(d.name);
    try {
      if (d.kind == CurveDescription::Kind::Polyline) {
        net.curves.push_back(interpolateCubicSpline(d.points, d.closed, d.spacing));
      } else {
        net.curves.push_back(bsplineCurve(d.points, d.degree, d.knots, d.closed));
      }
    } catch (const CurveInputError& e) {
      throw CurveInputError(curveLabel(net, c) + ": " + e.what());
    }
    if (!(d.influence > 0.0)) {
      throw CurveInputError(curveLabel(net, c) + ": influence weight must be > 0, got " +
                            std::to_string(d.influence));
    }
    net.influence.push_back(d.influence);
    if (d.plane) {
      Plane p = *d.plane;
      if (!(p.normal.norm() > 0.0)) {
        throw CurveInputError(curveLabel(net, c) + ": plane normal must be nonzero");
      }
      p.normal.normalize();
      net.planes.push_back(p);
    } else {
      net.planes.push_back(fitCurvePlane(net.curves.back()));
    }
  }
  constexpr int kSamples = 8;
  std::vector<Eigen::MatrixX3d> samples(nc);
  std::vector<Eigen::VectorXd> params(nc);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (int c = 0; c < nc; ++c) {
    net.curves[c].sample(kSamples, samples[c], params[c]);
    lo = lo.cwiseMin(samples[c].colwise().minCoeff().transpose());
    hi = hi.cwiseMax(samples[c].colwise().maxCoeff().transpose());
  }
  net.scale = (hi - lo).norm();
  const double tau = options.intersectionTolerance > 0.0 ? options.intersectionTolerance
                                                         : 0.01 * net.scale;
  net.tolerance = tau;
  const double sinMin = std::sin(options.minimumCrossingAngleDegrees * std::numbers::pi / 180.0);

  // --- pairwise intersections (closest points), Kuriyama 1996, sec. 5.3.3 steps 1-2
  // ------------------------------
  std::vector<PairHit> hits;
  // Per-segment sample boxes: only segment pairs whose boxes come within the gate are compared.
  std::vector<double> step(nc, 0.0);
  std::vector<std::vector<Eigen::AlignedBox3d>> boxes(nc);
  for (int c = 0; c < nc; ++c) {
    const Eigen::MatrixX3d& p = samples[c];
    const Eigen::Index n = p.rows();
    for (Eigen::Index i = 1; i < n; ++i) step[c] = std::max(step[c], (p.row(i) - p.row(i - 1)).norm());
    if (net.curves[c].closed()) step[c] = std::max(step[c], (p.row(0) - p.row(n - 1)).norm());
    const int segs = static_cast<int>(net.curves[c].segments().size());
    for (int k = 0; k < segs; ++k) {
      Eigen::AlignedBox3d box;
      for (int q = 0; q <= kSamples; ++q) {
        const Eigen::Index idx = net.curves[c].closed() ? (k * kSamples + q) % n : std::min<Eigen::Index>(k * kSamples + q, n - 1);
        box.extend(p.row(idx).transpose());
      }
      boxes[c].push_back(box);
    }
  }
  for (int a = 0; a < nc; ++a) {
    for (int b = a + 1; b < nc; ++b) {
      const double gate = tau + step[a] + step[b];
      Eigen::Index r0 = std::numeric_limits<Eigen::Index>::max(), r1 = -1, c0 = r0, c1 = -1;
      for (int ka = 0; ka < static_cast<int>(boxes[a].size()); ++ka) {
        Eigen::AlignedBox3d grown = boxes[a][ka];
        grown.min().array() -= gate;
        grown.max().array() += gate;
        for (int kb = 0; kb < static_cast<int>(boxes[b].size()); ++kb) {
          if (!grown.intersects(boxes[b][kb])) continue;
          r0 = std::min<Eigen::Index>(r0, ka * kSamples);
          r1 = std::max<Eigen::Index>(r1, (ka + 1) * kSamples);
          c0 = std::min<Eigen::Index>(c0, kb * kSamples);
          c1 = std::max<Eigen::Index>(c1, (kb + 1) * kSamples);
        }
      }
      if (r1 < 0) continue;
      const Eigen::Index naAll = samples[a].rows(), nbAll = samples[b].rows();
      r1 = std::min(r1, naAll - 1);
      c1 = std::min(c1, nbAll - 1);
      // Wrap-around neighbours only when the window is the whole closed curve.
      const bool wrapA = net.curves[a].closed() && r0 == 0 && r1 == naAll - 1;
      const bool wrapB = net.curves[b].closed() && c0 == 0 && c1 == nbAll - 1;
      const Eigen::MatrixX3d pa = samples[a].middleRows(r0, r1 - r0 + 1);
      const Eigen::MatrixX3d pb = samples[b].middleRows(c0, c1 - c0 + 1);
      const Eigen::Index na = pa.rows(), nb = pb.rows();
      Eigen::MatrixXd dist(na, nb);
      for (Eigen::Index i = 0; i < na; ++i) {
        dist.row(i) = (pb.rowwise() - pa.row(i)).rowwise().norm().transpose();
      }
      Eigen::Index mi = 0, mj = 0;
      if (dist.minCoeff(&mi, &mj) > gate) continue;
      std::vector<PairHit> pairHits;
      for (Eigen::Index i = 0; i < na; ++i) {
        for (Eigen::Index j = 0; j < nb; ++j) {
          const double dij = dist(i, j);
          if (dij > gate) continue;
          bool isMin = true;
          for (int di = -1; di <= 1 && isMin; ++di) {
            for (int dj = -1; dj <= 1 && isMin; ++dj) {
              if (di == 0 && dj == 0) continue;
              Eigen::Index ii = i + di, jj = j + dj;
              if (wrapA) ii = (ii + na) % na;
              if (wrapB) jj = (jj + nb) % nb;
              if (ii < 0 || ii >= na || jj < 0 || jj >= nb) continue;
              // Ties broken by index so a flat valley yields one start, not many.
              if (dist(ii, jj) < dij || (dist(ii, jj) == dij && (ii * nb + jj) < (i * nb + j))) {
                isMin = false;
              }
            }
          }
          if (!isMin) continue;
          double s = params[a][r0 + i], t = params[b][c0 + j];
          refineClosestPoints(net.curves[a], net.curves[b], s, t);
          // T-detection (Kuriyama 1996, sec. 5.3.3): an open end within tau of the other curve is
          // the cut point.
          if (snapToEnd(net.curves[a], s, tau)) refineOnOneCurve(net.curves[a].evaluate(s), net.curves[b], t);
          if (snapToEnd(net.curves[b], t, tau)) refineOnOneCurve(net.curves[b].evaluate(t), net.curves[a], s);
          const Eigen::Vector3d xa = net.curves[a].evaluate(s), xb = net.curves[b].evaluate(t);
          const double d = (xa - xb).norm();
          if (d >= tau) continue;
          PairHit hit{a, b, s, t, d, 0.5 * (xa + xb)};
          bool duplicate = false;
          for (PairHit& other : pairHits) {
            if ((other.point - hit.point).norm() < tau) {
              duplicate = true;
              if (hit.distance < other.distance) other = hit;
            }
          }
          if (!duplicate) pairHits.push_back(hit);
        }
      }
      if (pairHits.empty()) {
        // A near miss is the usual symptom of a crossing the designer meant: say where.
        double s = params[a][r0 + mi], t = params[b][c0 + mj];
        refineClosestPoints(net.curves[a], net.curves[b], s, t);
        const Eigen::Vector3d xa = net.curves[a].evaluate(s), xb = net.curves[b].evaluate(t);
        const double d = (xa - xb).norm();
        if (d < 3.0 * tau) {
          std::ostringstream msg;
          msg << curveLabel(net, a) << " and " << curveLabel(net, b) << " pass within " << d
              << " of each other near " << fmt(0.5 * (xa + xb)) << " without meeting (tolerance "
              << tau << "); raise the tolerance or move them if they should cross";
          net.notes.push_back(msg.str());
        }
      }
      for (const PairHit& hit : pairHits) {
        const Eigen::Vector3d ta = net.curves[a].evaluate(hit.ta, 1).normalized();
        const Eigen::Vector3d tb = net.curves[b].evaluate(hit.tb, 1).normalized();
        const double sine = ta.cross(tb).norm();
        if (sine < sinMin) {
          std::ostringstream msg;
          msg << curveLabel(net, a) << " and " << curveLabel(net, b)
              << " are tangent or nearly coincident near " << fmt(hit.point) << " (t = " << hit.ta
              << " and " << hit.tb << "): crossing angle "
              << std::asin(std::min(1.0, sine)) * 180.0 / std::numbers::pi << " deg, expected >= "
              << options.minimumCrossingAngleDegrees
              << " deg; separate the curves or make them cross";
          throw CurveNetworkError(msg.str());
        }
        hits.push_back(hit);
      }
    }
  }

  // --- vertices: clusters of hits closer than tau (>= 3 curves: a multiple point) -------------
  const int nh = static_cast<int>(hits.size());
  UnionFind uf(nh);
  for (int i = 0; i < nh; ++i) {
    for (int j = i + 1; j < nh; ++j) {
      if ((hits[i].point - hits[j].point).norm() < tau) uf.unite(i, j);
    }
  }
  std::map<int, std::vector<int>> clusters;
  for (int i = 0; i < nh; ++i) clusters[uf.find(i)].push_back(i);
  for (const auto& [root, members] : clusters) {
    std::map<int, std::vector<double>> perCurve;
    for (int h : members) {
      perCurve[hits[h].a].push_back(hits[h].ta);
      perCurve[hits[h].b].push_back(hits[h].tb);
    }
    NetworkVertex v;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    std::vector<Plane> planes;
    for (const auto& [c, ts] : perCurve) {
      const NetworkCurve& curve = net.curves[c];
      // Average near-equal parameters relative to the first, so a seam does not split them.
      double sum = 0.0;
      for (double t : ts) {
        double dt = t - ts.front();
        if (curve.closed()) dt -= curve.period() * std::round(dt / curve.period());
        sum += dt;
      }
      double t = ts.front() + sum / ts.size();
      if (endsAt(curve, ts.front())) t = ts.front();
      t = curve.wrap(t);
      v.curves.push_back({c, t});
      mean += curve.evaluate(t);
      if (net.planes[c]) planes.push_back(*net.planes[c]);
    }
    mean /= static_cast<double>(perCurve.size());
    v.position = projectOntoPlanes(mean, planes);
    int ending = 0;
    for (const CurvePoint& cp : v.curves) ending += endsAt(net.curves[cp.curve], cp.parameter) ? 1 : 0;
    if (v.curves.size() >= 3) {
      v.kind = NetworkVertex::Kind::Multiple;
    } else if (ending == 1) {
      v.kind = NetworkVertex::Kind::TJunction;
    } else {
      v.kind = NetworkVertex::Kind::Crossing;
    }
    net.vertices.push_back(v);
  }

  // --- curves meeting nothing ---------------------------------------------------------------
  std::vector<std::vector<std::pair<double, int>>> onCurve(nc);
  for (int vi = 0; vi < static_cast<int>(net.vertices.size()); ++vi) {
    for (const CurvePoint& cp : net.vertices[vi].curves) onCurve[cp.curve].push_back({cp.parameter, vi});
  }
  for (int c = 0; c < nc; ++c) {
    if (!onCurve[c].empty()) continue;
    // The nearest miss, only computed for the report.
    NearMiss miss;
    for (int o = 0; o < nc; ++o) {
      if (o == c) continue;
      for (Eigen::Index i = 0; i < samples[c].rows(); ++i) {
        Eigen::Index j = 0;
        const double d = (samples[o].rowwise() - samples[c].row(i)).rowwise().norm().minCoeff(&j);
        if (d < miss.distance) miss = {d, o, params[c][i], params[o][j]};
      }
    }
    std::ostringstream msg;
    msg << curveLabel(net, c) << " meets no other curve within tolerance " << tau;
    if (miss.other >= 0) {
      double ts = miss.tSelf, to = miss.tOther;
      refineClosestPoints(net.curves[c], net.curves[miss.other], ts, to);
      const Eigen::Vector3d ps = net.curves[c].evaluate(ts), po = net.curves[miss.other].evaluate(to);
      msg << ": nearest is " << curveLabel(net, miss.other) << " at distance "
          << (ps - po).norm() << " near " << fmt(0.5 * (ps + po)) << " (t = " << ts << ")"
          << "; move the curves together or raise the intersection tolerance";
    }
    throw CurveNetworkError(msg.str());
  }

  // --- curve correction, Kuriyama 1996, sec. 5.3.3
  // --------------------------------------------------------
  for (int c = 0; c < nc; ++c) {
    std::vector<double> ts;
    Eigen::MatrixX3d disp(onCurve[c].size(), 3);
    for (std::size_t k = 0; k < onCurve[c].size(); ++k) {
      ts.push_back(onCurve[c][k].first);
      disp.row(k) = (net.vertices[onCurve[c][k].second].position -
                     net.curves[c].evaluate(onCurve[c][k].first))
                        .transpose();
    }
    net.curves[c] = net.curves[c].plus(correctionSpline(net.curves[c], ts, disp));
    for (const auto& [t, vi] : onCurve[c]) {
      const double r = (net.curves[c].evaluate(t) - net.vertices[vi].position).norm();
      net.correctionResidual = std::max(net.correctionResidual, r);
      if (r > 1e-9 * net.scale) {
        std::ostringstream msg;
        msg << curveLabel(net, c) << ": curve correction cannot meet the intersection at "
            << fmt(net.vertices[vi].position) << " (t = " << t << "), residual " << r
            << " > 1e-9 L; the curve has too few knot spans for its intersections: add points";
        throw CurveNetworkError(msg.str());
      }
    }
  }

  // --- free ends, edges, half-edges, Kuriyama 1996, sec. 5.3.3
  // -----------------------------------------------------
  for (int c = 0; c < nc; ++c) {
    const NetworkCurve& curve = net.curves[c];
    if (!curve.closed()) {
      for (double tEnd : {curve.tMin(), curve.tMax()}) {
        bool present = false;
        for (const auto& [t, vi] : onCurve[c]) present = present || std::abs(t - tEnd) <= 1e-9 * curve.period();
        if (present) continue;
        NetworkVertex v;
        v.kind = NetworkVertex::Kind::FreeEnd;
        v.position = curve.evaluate(tEnd);
        v.curves.push_back({c, tEnd});
        net.vertices.push_back(v);
        onCurve[c].push_back({tEnd, static_cast<int>(net.vertices.size()) - 1});
      }
    }
    std::sort(onCurve[c].begin(), onCurve[c].end());
  }
  auto isFree = [&](int v) { return net.vertices[v].kind == NetworkVertex::Kind::FreeEnd; };
  std::vector<std::vector<int>> curveEdges(nc);  // forward half-edges along each curve, in order
  for (int c = 0; c < nc; ++c) {
    const NetworkCurve& curve = net.curves[c];
    const auto& list = onCurve[c];
    const int count = static_cast<int>(list.size());
    const int edges = curve.closed() ? count : count - 1;
    for (int k = 0; k < edges; ++k) {
      const auto& [t0, v0] = list[k];
      double t1 = (k + 1 < count) ? list[k + 1].first : list[0].first + curve.period();
      const int v1 = list[(k + 1) % count].second;
      HalfEdge fwd{c, v0, v1, t0, t1, 1, -1, -1, -1, -1, isFree(v0) || isFree(v1)};
      HalfEdge bwd{c, v1, v0, t1, t0, -1, -1, -1, -1, -1, fwd.dangling};
      const int id = static_cast<int>(net.halfEdges.size());
      fwd.twin = id + 1;
      bwd.twin = id;
      net.halfEdges.push_back(fwd);
      net.halfEdges.push_back(bwd);
      curveEdges[c].push_back(id);
    }
  }
  auto tangentOut = [&](const HalfEdge& h) -> Eigen::Vector3d {
    return h.sign * net.curves[h.curve].evaluate(h.tFrom, 1);
  };
  auto tangentIn = [&](const HalfEdge& h) -> Eigen::Vector3d {
    return h.sign * net.curves[h.curve].evaluate(h.tTo, 1);
  };

  // --- vertex normals, N.1-N.4 (Kuriyama 1996, sec. 5.3.3)
  // -------------------------------------------------------
  std::vector<int> orientation(nc, 0);  // +1: CCW about the plane normal, so T x n is outward
  for (int c = 0; c < nc; ++c) {
    if (!net.planes[c]) continue;
    const Eigen::Vector3d n = net.planes[c]->normal;
    const Eigen::MatrixX3d& p = samples[c];
    const Eigen::Vector3d centre = p.colwise().mean().transpose();
    double area = 0.0;
    for (Eigen::Index k = 0; k < p.rows(); ++k) {
      const Eigen::Vector3d p0 = p.row(k).transpose() - centre;
      const Eigen::Vector3d p1 = p.row((k + 1) % p.rows()).transpose() - centre;
      area += 0.5 * p0.cross(p1).dot(n);
    }
    const double extent = (p.colwise().maxCoeff() - p.colwise().minCoeff()).norm();
    if (std::abs(area) > 1e-6 * extent * extent) orientation[c] = area > 0.0 ? 1 : -1;
  }
  const int nv = static_cast<int>(net.vertices.size());
  std::vector<int> state(nv, 0);  // 0 unknown, 1 by rule, 2 propagated
  for (int vi = 0; vi < nv; ++vi) {
    NetworkVertex& v = net.vertices[vi];
    if (v.kind == NetworkVertex::Kind::FreeEnd) continue;
    Eigen::MatrixX3d tangents(v.curves.size(), 3);
    for (std::size_t k = 0; k < v.curves.size(); ++k) {
      tangents.row(k) = net.curves[v.curves[k].curve].evaluate(v.curves[k].parameter, 1).normalized().transpose();
    }
    Eigen::Vector3d n;
    if (v.curves.size() == 2) {
      const Eigen::Vector3d t0 = tangents.row(0).transpose(), t1 = tangents.row(1).transpose();
      n = t0.cross(t1).normalized();
    } else {
      Eigen::JacobiSVD<Eigen::MatrixX3d> svd(tangents, Eigen::ComputeFullV);
      n = svd.matrixV().col(2);
    }
    int pos = 0, neg = 0;
    for (std::size_t k = 0; k < v.curves.size(); ++k) {
      const int c = v.curves[k].curve;
      if (orientation[c] == 0) continue;
      const Eigen::Vector3d tk = tangents.row(k).transpose();
      const Eigen::Vector3d outward = orientation[c] * tk.cross(net.planes[c]->normal);
      const double vote = outward.dot(n);
      if (vote > 1e-9) ++pos;
      if (vote < -1e-9) ++neg;
    }
    if (neg > 0 && pos == 0) n = -n;
    v.normal = n;
    v.normalFromRule = (pos > 0) != (neg > 0);
    state[vi] = v.normalFromRule ? 1 : 0;
  }
  std::vector<std::vector<int>> outgoing(nv);
  for (int h = 0; h < static_cast<int>(net.halfEdges.size()); ++h) outgoing[net.halfEdges[h].from].push_back(h);
  auto propagate = [&](std::deque<int> queue) {
    while (!queue.empty()) {
      const int vi = queue.front();
      queue.pop_front();
      for (int h : outgoing[vi]) {
        const int w = net.halfEdges[h].to;
        if (state[w] != 0 || isFree(w)) continue;
        const double dot = net.vertices[w].normal.dot(net.vertices[vi].normal);
        if (std::abs(dot) < 0.1) continue;  // too far apart to compare signs reliably
        if (dot < 0.0) net.vertices[w].normal = -net.vertices[w].normal;
        state[w] = 2;
        queue.push_back(w);
      }
    }
  };
  {
    std::deque<int> seeds;
    for (int vi = 0; vi < nv; ++vi) {
      if (state[vi] == 1) seeds.push_back(vi);
    }
    propagate(seeds);
    for (int vi = 0; vi < nv; ++vi) {
      if (state[vi] != 0 || isFree(vi)) continue;
      if (net.vertices[vi].normal.dot(options.orientationHint) < 0.0) {
        net.vertices[vi].normal = -net.vertices[vi].normal;
      }
      state[vi] = 2;
      net.notes.push_back("vertex at " + fmt(net.vertices[vi].position) +
                          ": tangent-plane orientation undetermined by N.1-N.4, taken from the "
                          "orientation hint");
      propagate({vi});
    }
  }

  // --- deterministic next (Kuriyama 1996, sec. 5.3.3)
  // -------------------------------------------------------------
  const double epsS = options.straightAngleDegrees * std::numbers::pi / 180.0;
  auto turnAngle = [&](int hin, int hout) {
    const Eigen::Vector3d n = net.vertices[net.halfEdges[hin].to].normal;
    const Eigen::Vector3d tin = projectedUnit(tangentIn(net.halfEdges[hin]), n);
    const Eigen::Vector3d tout = projectedUnit(tangentOut(net.halfEdges[hout]), n);
    return std::atan2(tin.cross(tout).dot(n), tin.dot(tout));
  };
  const int nhe = static_cast<int>(net.halfEdges.size());
  for (int h = 0; h < nhe; ++h) {
    HalfEdge& he = net.halfEdges[h];
    if (isFree(he.to)) continue;
    int best = -1;
    double bestAngle = -10.0;
    for (int o : outgoing[he.to]) {
      if (o == he.twin) continue;
      const double th = turnAngle(h, o);
      if (th <= -epsS) continue;
      if (best >= 0 && std::abs(th - bestAngle) < 1e-6) {
        net.notes.push_back("ambiguous turn at vertex " + fmt(net.vertices[he.to].position) +
                            " arriving on " + curveLabel(net, he.curve));
      }
      if (th > bestAngle) {
        bestAngle = th;
        best = o;
      }
    }
    he.next = best;
  }
  std::vector<int> predecessors(nhe, 0);
  for (const HalfEdge& he : net.halfEdges) {
    if (he.next >= 0) ++predecessors[he.next];
  }
  for (int h = 0; h < nhe; ++h) {
    if (predecessors[h] > 1) {
      throw CurveNetworkError("face tracing is ambiguous at vertex " +
                              fmt(net.vertices[net.halfEdges[h].from].position) + " on " +
                              curveLabel(net, net.halfEdges[h].curve) +
                              ": check for curves that cross tangentially");
    }
  }

  // --- runs (Kuriyama 1996, sec. 5.3.4): break where another curve passes through or the curve
  // ends ---------------
  for (int c = 0; c < nc; ++c) {
    const NetworkCurve& curve = net.curves[c];
    auto isBreak = [&](int vi) {
      const NetworkVertex& v = net.vertices[vi];
      for (const CurvePoint& cp : v.curves) {
        if (cp.curve == c) {
          if (endsAt(curve, cp.parameter)) return true;
        } else if (!endsAt(net.curves[cp.curve], cp.parameter)) {
          return true;
        }
      }
      return false;
    };
    // Dangling pieces are runs of their own (they end at a free end, a break): they carry
    // the single sweeps of open regions (rule (c)).
    const std::vector<int>& edges = curveEdges[c];
    if (edges.empty()) continue;
    // Rotate a closed curve so that a run starts at its first edge.
    std::vector<int> ordered = edges;
    if (curve.closed()) {
      std::size_t first = 0;
      while (first < ordered.size() && !isBreak(net.halfEdges[ordered[first]].from)) ++first;
      if (first < ordered.size()) std::rotate(ordered.begin(), ordered.begin() + first, ordered.end());
    }
    Run run;
    auto finish = [&]() {
      if (run.edges.empty()) return;
      net.runs.push_back(run);
      run = Run{};
    };
    for (std::size_t k = 0; k < ordered.size(); ++k) {
      const HalfEdge& he = net.halfEdges[ordered[k]];
      if (!run.edges.empty() && (isBreak(he.from) || he.from != net.halfEdges[run.edges.back()].to)) finish();
      if (run.edges.empty()) {
        run.curve = c;
        run.tStart = he.tFrom;
        run.tEnd = he.tFrom;
        run.vertexStart = he.from;
      }
      run.edges.push_back(ordered[k]);
      run.tEnd += he.tTo - he.tFrom;
      run.vertexEnd = he.to;
    }
    finish();
  }
  std::vector<std::pair<int, int>> edgeRun(nhe, {-1, -1});  // half-edge -> (run, index in run)
  for (int r = 0; r < static_cast<int>(net.runs.size()); ++r) {
    Run& run = net.runs[r];
    for (int k = 0; k < static_cast<int>(run.edges.size()); ++k) {
      const int h = run.edges[k];
      edgeRun[h] = {r, k};
      edgeRun[net.halfEdges[h].twin] = {r, k};
      net.halfEdges[h].run = r;
      net.halfEdges[net.halfEdges[h].twin].run = r;
    }
    for (int end = 0; end < 2; ++end) {
      const int vi = end == 0 ? run.vertexStart : run.vertexEnd;
      const double t = end == 0 ? run.tStart : run.tEnd;
      const NetworkVertex& v = net.vertices[vi];
      Transversal tr;
      tr.vertex = vi;
      std::vector<CurvePoint> through, all;
      for (const CurvePoint& cp : v.curves) {
        if (cp.curve == run.curve) continue;
        all.push_back(cp);
        if (!endsAt(net.curves[cp.curve], cp.parameter)) through.push_back(cp);
      }
      tr.members = through.empty() ? all : through;
      const Eigen::Vector3d tc = net.curves[run.curve].evaluate(t, 1).normalized();
      double w = 0.0;
      for (const CurvePoint& cp : tr.members) {
        const Eigen::Vector3d tk = net.curves[cp.curve].evaluate(cp.parameter, 1).normalized();
        const double side = tc.cross(tk).dot(v.normal);
        if (std::abs(side) < sinMin) {
          throw CurveNetworkError(curveLabel(net, cp.curve) + " is tangent to " +
                                  curveLabel(net, run.curve) + " at " + fmt(v.position) +
                                  ": a transversal must cross the guide curve");
        }
        tr.directions.push_back(side > 0.0 ? 1 : -1);
        w += net.influence[cp.curve];
      }
      tr.influence = tr.members.empty() ? 1.0 : w / tr.members.size();
      if (tr.members.empty() && !isFree(vi)) {
        throw CurveNetworkError(curveLabel(net, run.curve) + ": run end at " + fmt(v.position) +
                                " has no transversal curve");
      }
      (end == 0 ? run.atStart : run.atEnd) = tr;
    }
  }

  // --- orbits of next: faces (cycles) and open chains ----------------------------------------
  // The side made of loop[q..e) (one run, consecutive edges), as a fraction of its run.
  auto makeSide = [&](const std::vector<int>& loop, int q, int e) {
    const HalfEdge& first = net.halfEdges[loop[q]];
    const auto [runId, kFirst] = edgeRun[loop[q]];
    const int kLast = edgeRun[loop[e - 1]].second;
    const Run& run = net.runs[runId];
    FaceSide side;
    side.run = runId;
    side.forward = first.sign > 0;
    side.startVertex = first.from;
    const int kLo = std::min(kFirst, kLast), kHi = std::max(kFirst, kLast);
    auto offset = [&](int k) {
      double sum = 0.0;
      for (int j = 0; j < k; ++j) sum += net.halfEdges[run.edges[j]].tTo - net.halfEdges[run.edges[j]].tFrom;
      return sum;
    };
    const int runLen = static_cast<int>(run.edges.size());
    side.rho0 = kLo == 0 ? 0.0 : offset(kLo) / run.delta();
    side.rho1 = kHi == runLen - 1 ? 1.0 : offset(kHi + 1) / run.delta();
    side.delta = (kLo == 0 && kHi == runLen - 1) ? run.delta() : (side.rho1 - side.rho0) * run.delta();
    return side;
  };
  auto isCorner = [&](int prev, int cur) {
    const bool same = net.halfEdges[prev].curve == net.halfEdges[cur].curve &&
                      net.halfEdges[prev].run == net.halfEdges[cur].run;
    return !(same && std::abs(turnAngle(prev, cur)) < epsS);
  };
  std::vector<char> visited(nhe, 0);
  std::vector<std::vector<int>> openFaces;
  auto describeChain = [&](const std::vector<int>& chain) {
    std::ostringstream s;
    s << "open region (not filled) along";
    int last = -1;
    for (int h : chain) {
      if (net.halfEdges[h].curve != last) s << " " << curveLabel(net, net.halfEdges[h].curve);
      last = net.halfEdges[h].curve;
    }
    const HalfEdge& end = net.halfEdges[chain.back()];
    if (isFree(end.to)) {
      s << "; it ends at the free end of " << curveLabel(net, end.curve) << " at "
        << fmt(net.vertices[end.to].position);
    } else {
      s << "; it ends at " << fmt(net.vertices[end.to].position)
        << " where no curve turns left (a reflex corner or the outer boundary)";
    }
    return s.str();
  };
  for (int h = 0; h < nhe; ++h) {
    if (predecessors[h] != 0 || visited[h]) continue;
    std::vector<int> chain;
    for (int cur = h; cur >= 0 && !visited[cur]; cur = net.halfEdges[cur].next) {
      visited[cur] = 1;
      chain.push_back(cur);
    }
    // A single dangling piece bounds nothing; a chain that turns at a vertex bounds an open region.
    if (chain.size() < 2) continue;
    const bool freeToFree = isFree(net.halfEdges[chain.front()].from) && isFree(net.halfEdges[chain.back()].to);
    if (options.fillOpenRegions && freeToFree) {
      openFaces.push_back(chain);
    } else {
      net.openChains.push_back({chain, describeChain(chain)});
    }
  }
  for (int h = 0; h < nhe; ++h) {
    if (visited[h]) continue;
    std::vector<int> cycle;
    for (int cur = h; !visited[cur]; cur = net.halfEdges[cur].next) {
      visited[cur] = 1;
      cycle.push_back(cur);
    }
    // Corners: every vertex of the cycle except straight continuations on the same curve.
    const int len = static_cast<int>(cycle.size());
    std::vector<char> corner(len, 0);
    for (int q = 0; q < len; ++q) {
      corner[q] = isCorner(cycle[(q - 1 + len) % len], cycle[q]);
    }
    const int firstCorner = static_cast<int>(std::find(corner.begin(), corner.end(), 1) - corner.begin());
    if (firstCorner == len) {
      throw CurveNetworkError("a region bounded by " + curveLabel(net, net.halfEdges[cycle[0]].curve) +
                              " alone (one side, no corner) near " +
                              fmt(net.vertices[net.halfEdges[cycle[0]].from].position) +
                              " is not supported: add a curve across it");
    }
    std::rotate(cycle.begin(), cycle.begin() + firstCorner, cycle.end());
    std::rotate(corner.begin(), corner.begin() + firstCorner, corner.end());
    Face face;
    face.halfEdges = cycle;
    const int faceId = static_cast<int>(net.faces.size());
    for (int q = 0; q < len;) {
      int e = q + 1;
      while (e < len && !corner[e]) ++e;
      face.sides.push_back(makeSide(cycle, q, e));
      q = e;
    }
    if (face.sides.size() == 1) {
      throw CurveNetworkError("a region bounded by " + curveLabel(net, net.runs[face.sides[0].run].curve) +
                              " alone (one corner) near " +
                              fmt(net.vertices[net.halfEdges[cycle[0]].from].position) +
                              " is not supported: add a curve across it");
    }
    if (face.sides.size() == 2) {
      // Rule (d): halve both sides, each half a sub-range of its run, T-junction style.
      std::vector<FaceSide> four;
      for (const FaceSide& s : face.sides) {
        const double mid = 0.5 * (s.rho0 + s.rho1);
        FaceSide lower = s, upper = s;
        lower.rho1 = mid;
        upper.rho0 = mid;
        lower.delta = upper.delta = 0.5 * s.delta;
        if (s.forward) {
          upper.startVertex = -1;
          four.push_back(lower);
          four.push_back(upper);
        } else {
          lower.startVertex = -1;
          four.push_back(upper);
          four.push_back(lower);
        }
      }
      face.sides = four;
      face.twoCurveRegion = true;
    }
    for (int hh : cycle) net.halfEdges[hh].face = faceId;
    net.faces.push_back(face);
  }
  // Rule (c): an open chain between two free ends closed by a virtual side (opt-in,
  // Kuriyama 1996, sec. 5.2.4 (c)).
  for (const std::vector<int>& chain : openFaces) {
    Face face;
    face.halfEdges = chain;
    face.openRegion = true;
    const int len = static_cast<int>(chain.size());
    for (int q = 0; q < len;) {
      int e = q + 1;
      while (e < len && !isCorner(chain[e - 1], chain[e])) ++e;
      face.sides.push_back(makeSide(chain, q, e));
      q = e;
    }
    if (face.sides.size() < 2) {
      net.notes.push_back("open region along " + curveLabel(net, net.halfEdges[chain[0]].curve) +
                          " alone is not filled (needs >= 2 real sides)");
      continue;
    }
    FaceSide virtualSide;
    virtualSide.run = -1;
    virtualSide.startVertex = net.halfEdges[chain.back()].to;
    face.sides.push_back(virtualSide);
    const int faceId = static_cast<int>(net.faces.size());
    for (int hh : chain) net.halfEdges[hh].face = faceId;
    net.faces.push_back(face);
  }
  for (const OpenChain& chain : net.openChains) net.notes.push_back(chain.description);
  return net;
}

}  // namespace ffdkit::geometry::curvenet
