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

#include "curve_intersections.h"
#include "curve_point_search.h"

namespace ffdkit::geometry::curvenet {
namespace {

using namespace detail;

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

namespace {

// buildCurveNetwork's steps (Kuriyama 1996, sec. 5.3.3-5.3.4), in the order they run; each
// reads what the steps before it left in the builder.
class NetworkBuilder {
 public:
  explicit NetworkBuilder(const CurveNetworkOptions& options) : options_(options) {}

  CurveNetwork build(const CurveNetworkDescription& description) {
    makeCurves(description);
    sampleCurves();
    makeVertices(findIntersections());
    requireEveryCurveMeetsAnother();
    correctCurves();
    addFreeEndsAndHalfEdges();
    orientVertexNormals();
    chooseNextHalfEdges();
    makeRuns();
    traceFaces();
    for (const OpenChain& chain : net_.openChains) net_.notes.push_back(chain.description);
    return std::move(net_);
  }

 private:
  static constexpr int kSamples = 8;  // samples per curve segment

  // --- curves -------------------------------------------------------------------------------
  void makeCurves(const CurveNetworkDescription& description) {
    nc_ = static_cast<int>(description.curves.size());
    if (nc_ < 2) throw CurveNetworkError("a curve network needs >= 2 curves, got " + std::to_string(nc_));
    for (int c = 0; c < nc_; ++c) {
      const CurveDescription& d = description.curves[c];
      net_.curveNames.push_back(d.name);
      try {
        if (d.kind == CurveDescription::Kind::Polyline) {
          net_.curves.push_back(interpolateCubicSpline(d.points, d.closed, d.spacing));
        } else {
          net_.curves.push_back(bsplineCurve(d.points, d.degree, d.knots, d.closed));
        }
      } catch (const CurveInputError& e) {
        throw CurveInputError(curveLabel(net_, c) + ": " + e.what());
      }
      if (!(d.influence > 0.0)) {
        throw CurveInputError(curveLabel(net_, c) + ": influence weight must be > 0, got " + std::to_string(d.influence));
      }
      net_.influence.push_back(d.influence);
      if (d.plane) {
        Plane p = *d.plane;
        if (!(p.normal.norm() > 0.0)) throw CurveInputError(curveLabel(net_, c) + ": plane normal must be nonzero");
        p.normal.normalize();
        net_.planes.push_back(p);
      } else {
        net_.planes.push_back(fitCurvePlane(net_.curves.back()));
      }
    }
  }

  // Samples of every curve; the network's scale and the intersection tolerance from them.
  void sampleCurves() {
    samples_.resize(nc_);
    params_.resize(nc_);
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    for (int c = 0; c < nc_; ++c) {
      net_.curves[c].sample(kSamples, samples_[c], params_[c]);
      lo = lo.cwiseMin(samples_[c].colwise().minCoeff().transpose());
      hi = hi.cwiseMax(samples_[c].colwise().maxCoeff().transpose());
    }
    net_.scale = (hi - lo).norm();
    tau_ = options_.intersectionTolerance > 0.0 ? options_.intersectionTolerance : 0.01 * net_.scale;
    net_.tolerance = tau_;
    sinMin_ = std::sin(options_.minimumCrossingAngleDegrees * std::numbers::pi / 180.0);
  }

  // --- pairwise intersections (closest points), Kuriyama 1996, sec. 5.3.3 steps 1-2 ----------
  std::vector<PairHit> findIntersections() {
    return findCurveIntersections(net_, CurveSamples{samples_, params_, kSamples}, tau_,
                                  options_.minimumCrossingAngleDegrees);
  }

  // --- vertices: clusters of hits closer than tau (>= 3 curves: a multiple point) -------------
  void makeVertices(const std::vector<PairHit>& hits) {
    const int nh = static_cast<int>(hits.size());
    UnionFind uf(nh);
    for (int i = 0; i < nh; ++i)
      for (int j = i + 1; j < nh; ++j)
        if ((hits[i].point - hits[j].point).norm() < tau_) uf.unite(i, j);
    std::map<int, std::vector<int>> clusters;
    for (int i = 0; i < nh; ++i) clusters[uf.find(i)].push_back(i);
    for (const auto& [root, members] : clusters) {
      std::map<int, std::vector<double>> perCurve;
      for (int h : members) {
        perCurve[hits[h].a].push_back(hits[h].ta);
        perCurve[hits[h].b].push_back(hits[h].tb);
      }
      net_.vertices.push_back(vertexOf(perCurve));
    }
  }

  // The vertex where the curves of `perCurve` meet at (about) the parameters given.
  NetworkVertex vertexOf(const std::map<int, std::vector<double>>& perCurve) const {
    NetworkVertex v;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    std::vector<Plane> planes;
    for (const auto& [c, ts] : perCurve) {
      const NetworkCurve& curve = net_.curves[c];
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
      if (net_.planes[c]) planes.push_back(*net_.planes[c]);
    }
    mean /= static_cast<double>(perCurve.size());
    v.position = projectOntoPlanes(mean, planes);
    int ending = 0;
    for (const CurvePoint& cp : v.curves) ending += endsAt(net_.curves[cp.curve], cp.parameter) ? 1 : 0;
    if (v.curves.size() >= 3) {
      v.kind = NetworkVertex::Kind::Multiple;
    } else if (ending == 1) {
      v.kind = NetworkVertex::Kind::TJunction;
    } else {
      v.kind = NetworkVertex::Kind::Crossing;
    }
    return v;
  }

  // --- curves meeting nothing ---------------------------------------------------------------
  void requireEveryCurveMeetsAnother() {
    onCurve_.assign(nc_, {});
    for (int vi = 0; vi < static_cast<int>(net_.vertices.size()); ++vi)
      for (const CurvePoint& cp : net_.vertices[vi].curves) onCurve_[cp.curve].push_back({cp.parameter, vi});
    for (int c = 0; c < nc_; ++c)
      if (onCurve_[c].empty()) throw CurveNetworkError(lonelyCurveMessage(c));
  }

  // What to say of a curve that meets no other: its nearest miss, computed only for the report.
  std::string lonelyCurveMessage(int c) const {
    NearMiss miss;
    for (int o = 0; o < nc_; ++o) {
      if (o == c) continue;
      for (Eigen::Index i = 0; i < samples_[c].rows(); ++i) {
        Eigen::Index j = 0;
        const double d = (samples_[o].rowwise() - samples_[c].row(i)).rowwise().norm().minCoeff(&j);
        if (d < miss.distance) miss = {d, o, params_[c][i], params_[o][j]};
      }
    }
    std::ostringstream msg;
    msg << curveLabel(net_, c) << " meets no other curve within tolerance " << tau_;
    if (miss.other >= 0) {
      double ts = miss.tSelf, to = miss.tOther;
      refineClosestPoints(net_.curves[c], net_.curves[miss.other], ts, to);
      const Eigen::Vector3d ps = net_.curves[c].evaluate(ts), po = net_.curves[miss.other].evaluate(to);
      msg << ": nearest is " << curveLabel(net_, miss.other) << " at distance " << (ps - po).norm() << " near "
          << formatPoint(0.5 * (ps + po)) << " (t = " << ts << ")"
          << "; move the curves together or raise the intersection tolerance";
    }
    return msg.str();
  }

  // --- curve correction, Kuriyama 1996, sec. 5.3.3 --------------------------------------------
  void correctCurves() {
    for (int c = 0; c < nc_; ++c) {
      std::vector<double> ts;
      Eigen::MatrixX3d disp(onCurve_[c].size(), 3);
      for (std::size_t k = 0; k < onCurve_[c].size(); ++k) {
        ts.push_back(onCurve_[c][k].first);
        disp.row(k) =
            (net_.vertices[onCurve_[c][k].second].position - net_.curves[c].evaluate(onCurve_[c][k].first)).transpose();
      }
      net_.curves[c] = net_.curves[c].plus(correctionSpline(net_.curves[c], ts, disp));
      for (const auto& [t, vi] : onCurve_[c]) {
        const double r = (net_.curves[c].evaluate(t) - net_.vertices[vi].position).norm();
        net_.correctionResidual = std::max(net_.correctionResidual, r);
        if (r > 1e-9 * net_.scale) {
          std::ostringstream msg;
          msg << curveLabel(net_, c) << ": curve correction cannot meet the intersection at "
              << formatPoint(net_.vertices[vi].position) << " (t = " << t << "), residual " << r
              << " > 1e-9 L; the curve has too few knot spans for its intersections: add points";
          throw CurveNetworkError(msg.str());
        }
      }
    }
  }

  // --- free ends, edges, half-edges, Kuriyama 1996, sec. 5.3.3 --------------------------------
  void addFreeEndsAndHalfEdges() {
    for (int c = 0; c < nc_; ++c) {
      const NetworkCurve& curve = net_.curves[c];
      if (!curve.closed()) {
        for (double tEnd : {curve.tMin(), curve.tMax()}) {
          bool present = false;
          for (const auto& [t, vi] : onCurve_[c]) present = present || std::abs(t - tEnd) <= 1e-9 * curve.period();
          if (present) continue;
          NetworkVertex v;
          v.kind = NetworkVertex::Kind::FreeEnd;
          v.position = curve.evaluate(tEnd);
          v.curves.push_back({c, tEnd});
          net_.vertices.push_back(v);
          onCurve_[c].push_back({tEnd, static_cast<int>(net_.vertices.size()) - 1});
        }
      }
      std::sort(onCurve_[c].begin(), onCurve_[c].end());
    }
    curveEdges_.assign(nc_, {});  // forward half-edges along each curve, in order
    for (int c = 0; c < nc_; ++c) {
      const NetworkCurve& curve = net_.curves[c];
      const auto& list = onCurve_[c];
      const int count = static_cast<int>(list.size());
      const int edges = curve.closed() ? count : count - 1;
      for (int k = 0; k < edges; ++k) {
        const auto& [t0, v0] = list[k];
        double t1 = (k + 1 < count) ? list[k + 1].first : list[0].first + curve.period();
        const int v1 = list[(k + 1) % count].second;
        HalfEdge fwd{c, v0, v1, t0, t1, 1, -1, -1, -1, -1, isFree(v0) || isFree(v1)};
        HalfEdge bwd{c, v1, v0, t1, t0, -1, -1, -1, -1, -1, fwd.dangling};
        const int id = static_cast<int>(net_.halfEdges.size());
        fwd.twin = id + 1;
        bwd.twin = id;
        net_.halfEdges.push_back(fwd);
        net_.halfEdges.push_back(bwd);
        curveEdges_[c].push_back(id);
      }
    }
    outgoing_.assign(net_.vertices.size(), {});
    for (int h = 0; h < static_cast<int>(net_.halfEdges.size()); ++h) outgoing_[net_.halfEdges[h].from].push_back(h);
  }

  bool isFree(int v) const { return net_.vertices[v].kind == NetworkVertex::Kind::FreeEnd; }
  Eigen::Vector3d tangentOut(const HalfEdge& h) const { return h.sign * net_.curves[h.curve].evaluate(h.tFrom, 1); }
  Eigen::Vector3d tangentIn(const HalfEdge& h) const { return h.sign * net_.curves[h.curve].evaluate(h.tTo, 1); }

  // --- vertex normals, N.1-N.4 (Kuriyama 1996, sec. 5.3.3) ------------------------------------
  void orientVertexNormals() {
    const std::vector<int> orientation = planarCurveOrientations();
    const int nv = static_cast<int>(net_.vertices.size());
    normalState_.assign(nv, 0);  // 0 unknown, 1 by rule, 2 propagated
    for (int vi = 0; vi < nv; ++vi) {
      NetworkVertex& v = net_.vertices[vi];
      if (v.kind == NetworkVertex::Kind::FreeEnd) continue;
      normalByRule(v, orientation);
      normalState_[vi] = v.normalFromRule ? 1 : 0;
    }
    std::deque<int> seeds;
    for (int vi = 0; vi < nv; ++vi)
      if (normalState_[vi] == 1) seeds.push_back(vi);
    propagateNormals(seeds);
    for (int vi = 0; vi < nv; ++vi) {
      if (normalState_[vi] != 0 || isFree(vi)) continue;
      if (net_.vertices[vi].normal.dot(options_.orientationHint) < 0.0) net_.vertices[vi].normal = -net_.vertices[vi].normal;
      normalState_[vi] = 2;
      net_.notes.push_back("vertex at " + formatPoint(net_.vertices[vi].position) +
                           ": tangent-plane orientation undetermined by N.1-N.4, taken from the "
                           "orientation hint");
      propagateNormals({vi});
    }
  }

  // Per curve with a plane, +1 when it runs CCW about the plane normal (so T x n points
  // outward), -1 when CW, 0 when it has no plane or encloses no area.
  std::vector<int> planarCurveOrientations() const {
    std::vector<int> orientation(nc_, 0);
    for (int c = 0; c < nc_; ++c) {
      if (!net_.planes[c]) continue;
      const Eigen::Vector3d n = net_.planes[c]->normal;
      const Eigen::MatrixX3d& p = samples_[c];
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
    return orientation;
  }

  // The vertex's normal across its curves' tangents, its sign voted by the planar curves'
  // outward directions; normalFromRule when the vote is unanimous.
  void normalByRule(NetworkVertex& v, const std::vector<int>& orientation) const {
    Eigen::MatrixX3d tangents(v.curves.size(), 3);
    for (std::size_t k = 0; k < v.curves.size(); ++k)
      tangents.row(k) = net_.curves[v.curves[k].curve].evaluate(v.curves[k].parameter, 1).normalized().transpose();
    Eigen::Vector3d n;
    if (v.curves.size() == 2) {
      const Eigen::Vector3d t0 = tangents.row(0).transpose(), t1 = tangents.row(1).transpose();
      n = t0.cross(t1).normalized();
    } else {
      // Dynamic size: the SVD of a MatrixX3d is a template instance of its own that took two
      // thirds of this file's compile time; the same bits (compared on 300,000 tangent sets).
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(tangents, Eigen::ComputeFullV);
      n = svd.matrixV().col(2);
    }
    int pos = 0, neg = 0;
    for (std::size_t k = 0; k < v.curves.size(); ++k) {
      const int c = v.curves[k].curve;
      if (orientation[c] == 0) continue;
      const Eigen::Vector3d tk = tangents.row(k).transpose();
      const Eigen::Vector3d outward = orientation[c] * tk.cross(net_.planes[c]->normal);
      const double vote = outward.dot(n);
      if (vote > 1e-9) ++pos;
      if (vote < -1e-9) ++neg;
    }
    if (neg > 0 && pos == 0) n = -n;
    v.normal = n;
    v.normalFromRule = (pos > 0) != (neg > 0);
  }

  // Gives the neighbours of the queued vertices (breadth first) the sign of their normals.
  void propagateNormals(std::deque<int> queue) {
    while (!queue.empty()) {
      const int vi = queue.front();
      queue.pop_front();
      for (int h : outgoing_[vi]) {
        const int w = net_.halfEdges[h].to;
        if (normalState_[w] != 0 || isFree(w)) continue;
        const double dot = net_.vertices[w].normal.dot(net_.vertices[vi].normal);
        if (std::abs(dot) < 0.1) continue;  // too far apart to compare signs reliably
        if (dot < 0.0) net_.vertices[w].normal = -net_.vertices[w].normal;
        normalState_[w] = 2;
        queue.push_back(w);
      }
    }
  }

  // --- deterministic next (Kuriyama 1996, sec. 5.3.3) -----------------------------------------
  double turnAngle(int hin, int hout) const {
    const Eigen::Vector3d n = net_.vertices[net_.halfEdges[hin].to].normal;
    const Eigen::Vector3d tin = projectedUnit(tangentIn(net_.halfEdges[hin]), n);
    const Eigen::Vector3d tout = projectedUnit(tangentOut(net_.halfEdges[hout]), n);
    return std::atan2(tin.cross(tout).dot(n), tin.dot(tout));
  }

  // Each half-edge's next: the leftmost turn at its end vertex (none beyond -epsS).
  void chooseNextHalfEdges() {
    epsS_ = options_.straightAngleDegrees * std::numbers::pi / 180.0;
    nhe_ = static_cast<int>(net_.halfEdges.size());
    for (int h = 0; h < nhe_; ++h) {
      HalfEdge& he = net_.halfEdges[h];
      if (isFree(he.to)) continue;
      int best = -1;
      double bestAngle = -10.0;
      for (int o : outgoing_[he.to]) {
        if (o == he.twin) continue;
        const double th = turnAngle(h, o);
        if (th <= -epsS_) continue;
        if (best >= 0 && std::abs(th - bestAngle) < 1e-6) {
          net_.notes.push_back("ambiguous turn at vertex " + formatPoint(net_.vertices[he.to].position) + " arriving on " +
                               curveLabel(net_, he.curve));
        }
        if (th > bestAngle) {
          bestAngle = th;
          best = o;
        }
      }
      he.next = best;
    }
    predecessors_.assign(nhe_, 0);
    for (const HalfEdge& he : net_.halfEdges)
      if (he.next >= 0) ++predecessors_[he.next];
    for (int h = 0; h < nhe_; ++h) {
      if (predecessors_[h] > 1) {
        throw CurveNetworkError("face tracing is ambiguous at vertex " + formatPoint(net_.vertices[net_.halfEdges[h].from].position) +
                                " on " + curveLabel(net_, net_.halfEdges[h].curve) +
                                ": check for curves that cross tangentially");
      }
    }
  }

  // --- runs (Kuriyama 1996, sec. 5.3.4): break where another curve passes through or the curve
  // ends ---------------------------------------------------------------------------------------
  void makeRuns() {
    for (int c = 0; c < nc_; ++c) makeRunsOf(c);
    edgeRun_.assign(nhe_, {-1, -1});  // half-edge -> (run, index in run)
    for (int r = 0; r < static_cast<int>(net_.runs.size()); ++r) {
      Run& run = net_.runs[r];
      for (int k = 0; k < static_cast<int>(run.edges.size()); ++k) {
        const int h = run.edges[k];
        edgeRun_[h] = {r, k};
        edgeRun_[net_.halfEdges[h].twin] = {r, k};
        net_.halfEdges[h].run = r;
        net_.halfEdges[net_.halfEdges[h].twin].run = r;
      }
      run.atStart = transversalAt(run, run.vertexStart, run.tStart);
      run.atEnd = transversalAt(run, run.vertexEnd, run.tEnd);
    }
  }

  // Whether a run of curve c breaks at vertex vi: c ends there, or another curve passes through.
  bool isRunBreak(int c, int vi) const {
    const NetworkVertex& v = net_.vertices[vi];
    for (const CurvePoint& cp : v.curves) {
      if (cp.curve == c) {
        if (endsAt(net_.curves[c], cp.parameter)) return true;
      } else if (!endsAt(net_.curves[cp.curve], cp.parameter)) {
        return true;
      }
    }
    return false;
  }

  void makeRunsOf(int c) {
    // Dangling pieces are runs of their own (they end at a free end, a break): they carry
    // the single sweeps of open regions (rule (c)).
    const std::vector<int>& edges = curveEdges_[c];
    if (edges.empty()) return;
    // Rotate a closed curve so that a run starts at its first edge.
    std::vector<int> ordered = edges;
    if (net_.curves[c].closed()) {
      std::size_t first = 0;
      while (first < ordered.size() && !isRunBreak(c, net_.halfEdges[ordered[first]].from)) ++first;
      if (first < ordered.size()) std::rotate(ordered.begin(), ordered.begin() + first, ordered.end());
    }
    Run run;
    auto finish = [&]() {
      if (run.edges.empty()) return;
      net_.runs.push_back(run);
      run = Run{};
    };
    for (std::size_t k = 0; k < ordered.size(); ++k) {
      const HalfEdge& he = net_.halfEdges[ordered[k]];
      if (!run.edges.empty() && (isRunBreak(c, he.from) || he.from != net_.halfEdges[run.edges.back()].to)) finish();
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

  // The curves crossing `run` at its end vertex vi (at parameter t): those passing through, else
  // those ending there; each one's side, and their mean influence.
  Transversal transversalAt(const Run& run, int vi, double t) const {
    const NetworkVertex& v = net_.vertices[vi];
    Transversal tr;
    tr.vertex = vi;
    std::vector<CurvePoint> through, all;
    for (const CurvePoint& cp : v.curves) {
      if (cp.curve == run.curve) continue;
      all.push_back(cp);
      if (!endsAt(net_.curves[cp.curve], cp.parameter)) through.push_back(cp);
    }
    tr.members = through.empty() ? all : through;
    const Eigen::Vector3d tc = net_.curves[run.curve].evaluate(t, 1).normalized();
    double w = 0.0;
    for (const CurvePoint& cp : tr.members) {
      const Eigen::Vector3d tk = net_.curves[cp.curve].evaluate(cp.parameter, 1).normalized();
      const double side = tc.cross(tk).dot(v.normal);
      if (std::abs(side) < sinMin_) {
        throw CurveNetworkError(curveLabel(net_, cp.curve) + " is tangent to " + curveLabel(net_, run.curve) + " at " +
                                formatPoint(v.position) + ": a transversal must cross the guide curve");
      }
      tr.directions.push_back(side > 0.0 ? 1 : -1);
      w += net_.influence[cp.curve];
    }
    tr.influence = tr.members.empty() ? 1.0 : w / tr.members.size();
    if (tr.members.empty() && !isFree(vi)) {
      throw CurveNetworkError(curveLabel(net_, run.curve) + ": run end at " + formatPoint(v.position) + " has no transversal curve");
    }
    return tr;
  }

  // --- orbits of next: faces (cycles) and open chains ----------------------------------------
  void traceFaces() {
    visited_.assign(nhe_, 0);
    const std::vector<std::vector<int>> openFaces = traceOpenChains();
    for (int h = 0; h < nhe_; ++h) {
      if (visited_[h]) continue;
      std::vector<int> cycle;
      for (int cur = h; !visited_[cur]; cur = net_.halfEdges[cur].next) {
        visited_[cur] = 1;
        cycle.push_back(cur);
      }
      addCycleFace(std::move(cycle));
    }
    for (const std::vector<int>& chain : openFaces) addOpenRegionFace(chain);
  }

  // The chains of next that start at a half-edge nothing leads to: open regions; those between
  // two free ends are returned (to be filled, when asked), the others kept as open chains.
  std::vector<std::vector<int>> traceOpenChains() {
    std::vector<std::vector<int>> openFaces;
    for (int h = 0; h < nhe_; ++h) {
      if (predecessors_[h] != 0 || visited_[h]) continue;
      std::vector<int> chain;
      for (int cur = h; cur >= 0 && !visited_[cur]; cur = net_.halfEdges[cur].next) {
        visited_[cur] = 1;
        chain.push_back(cur);
      }
      // A single dangling piece bounds nothing; a chain that turns at a vertex bounds an open region.
      if (chain.size() < 2) continue;
      const bool freeToFree = isFree(net_.halfEdges[chain.front()].from) && isFree(net_.halfEdges[chain.back()].to);
      if (options_.fillOpenRegions && freeToFree) {
        openFaces.push_back(chain);
      } else {
        net_.openChains.push_back({chain, describeChain(chain)});
      }
    }
    return openFaces;
  }

  std::string describeChain(const std::vector<int>& chain) const {
    std::ostringstream s;
    s << "open region (not filled) along";
    int last = -1;
    for (int h : chain) {
      if (net_.halfEdges[h].curve != last) s << " " << curveLabel(net_, net_.halfEdges[h].curve);
      last = net_.halfEdges[h].curve;
    }
    const HalfEdge& end = net_.halfEdges[chain.back()];
    if (isFree(end.to)) {
      s << "; it ends at the free end of " << curveLabel(net_, end.curve) << " at " << formatPoint(net_.vertices[end.to].position);
    } else {
      s << "; it ends at " << formatPoint(net_.vertices[end.to].position)
        << " where no curve turns left (a reflex corner or the outer boundary)";
    }
    return s.str();
  }

  // Whether the boundary turns a corner from half-edge prev to cur (anything but a straight
  // continuation along the same run).
  bool isCorner(int prev, int cur) const {
    const bool same =
        net_.halfEdges[prev].curve == net_.halfEdges[cur].curve && net_.halfEdges[prev].run == net_.halfEdges[cur].run;
    return !(same && std::abs(turnAngle(prev, cur)) < epsS_);
  }

  // The side made of loop[q..e) (one run, consecutive edges), as a fraction of its run.
  FaceSide makeSide(const std::vector<int>& loop, int q, int e) const {
    const HalfEdge& first = net_.halfEdges[loop[q]];
    const auto [runId, kFirst] = edgeRun_[loop[q]];
    const int kLast = edgeRun_[loop[e - 1]].second;
    const Run& run = net_.runs[runId];
    FaceSide side;
    side.run = runId;
    side.forward = first.sign > 0;
    side.startVertex = first.from;
    const int kLo = std::min(kFirst, kLast), kHi = std::max(kFirst, kLast);
    auto offset = [&](int k) {
      double sum = 0.0;
      for (int j = 0; j < k; ++j) sum += net_.halfEdges[run.edges[j]].tTo - net_.halfEdges[run.edges[j]].tFrom;
      return sum;
    };
    const int runLen = static_cast<int>(run.edges.size());
    side.rho0 = kLo == 0 ? 0.0 : offset(kLo) / run.delta();
    side.rho1 = kHi == runLen - 1 ? 1.0 : offset(kHi + 1) / run.delta();
    side.delta = (kLo == 0 && kHi == runLen - 1) ? run.delta() : (side.rho1 - side.rho0) * run.delta();
    return side;
  }

  // A cycle of next: a face, its sides split at its corners (rule (d): a two-sided region's
  // sides are halved).
  void addCycleFace(std::vector<int> cycle) {
    // Corners: every vertex of the cycle except straight continuations on the same curve.
    const int len = static_cast<int>(cycle.size());
    std::vector<char> corner(len, 0);
    for (int q = 0; q < len; ++q) corner[q] = isCorner(cycle[(q - 1 + len) % len], cycle[q]);
    const int firstCorner = static_cast<int>(std::find(corner.begin(), corner.end(), 1) - corner.begin());
    if (firstCorner == len) {
      throw CurveNetworkError("a region bounded by " + curveLabel(net_, net_.halfEdges[cycle[0]].curve) +
                              " alone (one side, no corner) near " +
                              formatPoint(net_.vertices[net_.halfEdges[cycle[0]].from].position) +
                              " is not supported: add a curve across it");
    }
    std::rotate(cycle.begin(), cycle.begin() + firstCorner, cycle.end());
    std::rotate(corner.begin(), corner.begin() + firstCorner, corner.end());
    Face face;
    face.halfEdges = cycle;
    const int faceId = static_cast<int>(net_.faces.size());
    for (int q = 0; q < len;) {
      int e = q + 1;
      while (e < len && !corner[e]) ++e;
      face.sides.push_back(makeSide(cycle, q, e));
      q = e;
    }
    if (face.sides.size() == 1) {
      throw CurveNetworkError("a region bounded by " + curveLabel(net_, net_.runs[face.sides[0].run].curve) +
                              " alone (one corner) near " + formatPoint(net_.vertices[net_.halfEdges[cycle[0]].from].position) +
                              " is not supported: add a curve across it");
    }
    if (face.sides.size() == 2) {
      face.sides = halvedSides(face.sides);
      face.twoCurveRegion = true;
    }
    for (int hh : cycle) net_.halfEdges[hh].face = faceId;
    net_.faces.push_back(face);
  }

  // Rule (d): both sides of a two-sided region halved, each half a sub-range of its run,
  // T-junction style.
  static std::vector<FaceSide> halvedSides(const std::vector<FaceSide>& sides) {
    std::vector<FaceSide> four;
    for (const FaceSide& s : sides) {
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
    return four;
  }

  // Rule (c): an open chain between two free ends closed by a virtual side (opt-in,
  // Kuriyama 1996, sec. 5.2.4 (c)).
  void addOpenRegionFace(const std::vector<int>& chain) {
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
      net_.notes.push_back("open region along " + curveLabel(net_, net_.halfEdges[chain[0]].curve) +
                           " alone is not filled (needs >= 2 real sides)");
      return;
    }
    FaceSide virtualSide;
    virtualSide.run = -1;
    virtualSide.startVertex = net_.halfEdges[chain.back()].to;
    face.sides.push_back(virtualSide);
    const int faceId = static_cast<int>(net_.faces.size());
    for (int hh : chain) net_.halfEdges[hh].face = faceId;
    net_.faces.push_back(face);
  }

  const CurveNetworkOptions& options_;
  CurveNetwork net_;
  int nc_ = 0;                                                  // curves
  std::vector<Eigen::MatrixX3d> samples_;                       // per curve, kSamples per segment
  std::vector<Eigen::VectorXd> params_;                         // the samples' parameters
  double tau_ = 0.0;                                            // intersection tolerance
  double sinMin_ = 0.0;                                         // sine of the least crossing angle
  std::vector<std::vector<std::pair<double, int>>> onCurve_;    // per curve, (parameter, vertex)
  std::vector<std::vector<int>> curveEdges_;                    // per curve, its forward half-edges
  std::vector<std::vector<int>> outgoing_;                      // per vertex, its half-edges
  std::vector<int> normalState_;                                // per vertex: 0 unknown, 1 rule, 2 propagated
  double epsS_ = 0.0;                                           // the straight-angle tolerance (radians)
  int nhe_ = 0;                                                 // half-edges
  std::vector<int> predecessors_;                               // per half-edge, how many lead to it
  std::vector<std::pair<int, int>> edgeRun_;                    // per half-edge, (run, index in run)
  std::vector<char> visited_;                                   // per half-edge, traced yet
};

}  // namespace

CurveNetwork buildCurveNetwork(const CurveNetworkDescription& description, const CurveNetworkOptions& options) {
  return NetworkBuilder(options).build(description);
}

}  // namespace ffdkit::geometry::curvenet
