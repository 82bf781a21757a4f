#include "ffdkit/geometry/polyhedron/patch_surface.h"

#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/Geometry>

#include "ffdkit/geometry/polyhedron/polyhedron_error.h"
#include "ffdkit/geometry/polyhedron/ring_targets.h"

namespace ffdkit::geometry::polyhedron {
namespace {

Eigen::Vector3d& subPointSlot(RationalQuarticTriangle& patch, int corner, int other) {
  return patch.subPoint(patch.cornerSlot(corner), patch.cornerSlot(other));
}

double boundaryKappa(int valence) {
  // Boundary edges need no G1; the mirrored ring of size M = 2 (N - 1) gives the regular value
  // (Kuriyama 1996, sec. 4.2.1).
  return 0.75 * std::cos(2.0 * std::numbers::pi / (2.0 * (valence - 1)));
}

}  // namespace

std::array<Eigen::Vector3d, 4> PatchSurface::curve(int a, int b) const {
  const MeshTopology& topo = triangulated_.topology;
  const int he = topo.findHalfEdge(a, b);
  if (he < 0) {
    throw PolyhedronError("network curve (" + std::to_string(a) + ", " + std::to_string(b) +
                          "): the triangulated network has no such edge");
  }
  const Eigen::Vector3d pa = triangulated_.points.row(a).transpose(), pb = triangulated_.points.row(b).transpose();
  return {pa, pa + triangulated_.legs.row(he).transpose(), pb + triangulated_.legs.row(topo.twin(he)).transpose(), pb};
}

PatchSurface PatchSurface::build(const PolygonMesh& mesh, const Tensions& tensions, const PatchSurfaceOptions& options) {
  PatchSurface s;
  s.mesh_ = mesh;
  s.topology_ = validatePolygonMesh(mesh);
  s.tensions_ = resolveTensions(tensions, s.topology_);
  s.network_ = solveCurveNetwork(mesh, s.topology_, s.tensions_, options.network);
  if (!s.network_.converged) throw PolyhedronError(s.network_.message);
  for (int v = 0; v < s.topology_.vertexCount(); ++v) {
    // t(theta) turns from T^c (theta = 0) to T^s (pi/2) counter-clockwise about the outward
    // normal, so T^c x T^s points out; compare with the area-weighted normal of the faces at v.
    Eigen::Vector3d faceNormal = Eigen::Vector3d::Zero();
    for (int he : s.topology_.ringHalfEdges(v)) {
      const int f = s.topology_.face(he);
      if (f < 0) continue;
      const auto& c = s.topology_.faceVertices(f);
      for (std::size_t k = 0; k < c.size(); ++k) {
        faceNormal += mesh.vertices.row(c[k]).cross(mesh.vertices.row(c[(k + 1) % c.size()])).transpose();
      }
    }
    const Frame& frame = s.network_.frames[v];
    if (frame.tc.cross(frame.ts).dot(faceNormal) < 0.0) {
      s.warnings_.push_back("vertex " + std::to_string(v) +
                            ": the tangent plane of the network faces against the polyhedron there (fold); "
                            "check the tensions or the vertex position");
    }
  }
  s.triangulated_ = splitFaces(mesh, s.topology_, s.network_, options.splitRule);
  for (int f = 0; f < s.topology_.faceCount(); ++f) {
    if (!s.triangulated_.splitPointInside[f]) {
      s.warnings_.push_back("face " + std::to_string(f) +
                            ": split point lies outside the face (concave face?); split it into convex faces "
                            "for an intuitive shape (Kuriyama 1996, sec. 4.3.4)");
    }
  }
  const TriangulatedNetwork& net = s.triangulated_;
  const MeshTopology& topo = net.topology;

  // Boundary control points: degree-elevated network cubics (eq. (4.12)).
  const int patchCount = static_cast<int>(net.triangles.rows());
  s.patches_.resize(patchCount);
  for (int t = 0; t < patchCount; ++t) {
    RationalQuarticTriangle& p = s.patches_[t];
    const int a = net.triangles(t, 0), b = net.triangles(t, 1), c = net.triangles(t, 2);
    p.corners = {a, b, c};
    const auto ab = elevateCubic(s.curve(a, b));
    const auto ac = elevateCubic(s.curve(a, c));
    const auto bc = elevateCubic(s.curve(b, c));
    for (int j = 0; j <= 4; ++j) {
      p.d[RationalQuarticTriangle::index(4 - j, j)] = ab[j];
      p.d[RationalQuarticTriangle::index(4 - j, 0)] = ac[j];
      p.d[RationalQuarticTriangle::index(0, 4 - j)] = bc[j];
    }
  }

  // G1 scalars per half-edge (Kuriyama 1996, sec. 4.3.1; default per-edge rule, sec. 4.2.2).
  s.g1_.assign(topo.halfEdgeCount(), {});
  for (int he = 0; he < topo.halfEdgeCount(); ++he) {
    const int p = topo.from(he);
    const int n = topo.valence(p);
    const bool boundaryEdge = topo.face(he) < 0 || topo.face(topo.twin(he)) < 0;
    EdgeG1Scalars& g = s.g1_[he];
    if (boundaryEdge) {
      g = {0.5, boundaryKappa(n)};
      continue;
    }
    if (options.g1Scalars == G1Scalars::ThesisConstants) {
      const int ringSize = topo.isBoundaryVertex(p) ? 2 * (n - 1) : n;
      g = {0.5, 0.75 * std::cos(2.0 * std::numbers::pi / ringSize)};
      continue;
    }
    const auto& ring = topo.ringHalfEdges(p);
    const int i = topo.ringIndex(he);
    const Eigen::Vector3d ti = net.legs.row(he).transpose();
    const Eigen::Vector3d prev = net.legs.row(ring[(i + n - 1) % n]).transpose();
    const Eigen::Vector3d next = net.legs.row(ring[(i + 1) % n]).transpose();
    Eigen::Matrix<double, 3, 2> m;
    m.col(0) = next - prev;
    m.col(1) = -ti;
    const Eigen::Vector2d x = m.colPivHouseholderQr().solve(-prev);
    const double residual = (m * x + prev).norm();
    if (!x.allFinite() || !(residual <= options.legFitTolerance * ti.norm()) || !(x[0] > 0.0 && x[0] < 1.0)) {
      throw PolyhedronError("G1 scalars at network vertex " + std::to_string(p) + ", edge to " +
                            std::to_string(topo.to(he)) + ": expected coplanar legs with 0 < omega < 1, got omega " +
                            std::to_string(x[0]) + ", residual " + std::to_string(residual));
    }
    g = {x[0], 0.75 * x[1]};
  }
  if (options.g1Scalars == G1Scalars::PerEdge) {
    for (int he = 0; he < topo.halfEdgeCount(); ++he) {
      const double sum = s.g1_[he].omega + s.g1_[topo.twin(he)].omega;
      if (std::abs(sum - 1.0) > 1e-8) {
        throw PolyhedronError("G1 weight of network edge (" + std::to_string(topo.from(he)) + ", " +
                              std::to_string(topo.to(he)) + "): the two ends disagree (omega + omega' = " +
                              std::to_string(sum) + ", expected 1)");
      }
    }
  }

  // rho_{P,e} of eq. (4.15) for the half-edge P -> P'.
  auto rho = [&](int he) -> Eigen::Vector3d {
    const auto v = s.curve(topo.from(he), topo.to(he));
    const double kp = s.g1_[he].kappa, kq = s.g1_[topo.twin(he)].kappa;
    return 2.0 / 3.0 * ((1.0 - kp) * v[1] + kp * v[2]) + 1.0 / 3.0 * (kq * v[0] + (1.0 - kq) * v[1]);
  };

  // Ring solves (Kuriyama 1996, secs. 4.3.1, 4.2.1): minimum-norm targets, then the per-edge
  // projection (4.19).
  std::vector<int> assigned(patchCount, 0);
  for (int p = 0; p < topo.vertexCount(); ++p) {
    const auto& ring = topo.ringHalfEdges(p);
    const int n = static_cast<int>(ring.size());
    Eigen::MatrixX3d r(n, 3);
    for (int i = 0; i < n; ++i) r.row(i) = 2.0 * rho(ring[i]).transpose();
    int ringSize = n;
    Eigen::MatrixX3d targets;
    if (!topo.isBoundaryVertex(p)) {
      targets = ringTargets(r);
    } else {
      // Reflect the ring in the plane through P spanned by the boundary tangent and the
      // tangent-plane normal, and solve it as a closed ring of size 2 (N - 1) (Kuriyama 1996,
      // sec. 4.2.1).
      ringSize = 2 * (n - 1);
      const Eigen::Vector3d origin = net.points.row(p).transpose();
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      for (int i = 0; i + 1 < n; ++i) normal += net.legs.row(ring[i]).cross(net.legs.row(ring[i + 1])).transpose();
      const Eigen::Vector3d mirror = net.legs.row(ring[0]).transpose().cross(normal).normalized();
      Eigen::MatrixX3d virtualRing(ringSize, 3);
      virtualRing.topRows(n) = r;
      for (int k = 1; k <= n - 2; ++k) {
        const Eigen::Vector3d x = r.row(n - 1 - k).transpose();
        virtualRing.row(n - 1 + k) = (x - 2.0 * (x - origin).dot(mirror) * mirror).transpose();
      }
      targets = ringTargets(virtualRing);
    }
    for (int i = 0; i < n; ++i) {
      const int he = ring[i];
      const double omega = s.g1_[he].omega;
      const Eigen::Vector3d gi = targets.row(i).transpose();
      const Eigen::Vector3d gPrev = targets.row((i + ringSize - 1) % ringSize).transpose();
      const Eigen::Vector3d lambda =
          (0.5 * r.row(i).transpose() - omega * gi - (1.0 - omega) * gPrev) / (omega * omega + (1.0 - omega) * (1.0 - omega));
      if (topo.face(he) >= 0) {
        subPointSlot(s.patches_[topo.face(he)], p, topo.to(he)) = gi + omega * lambda;
        ++assigned[topo.face(he)];
      }
      const int before = topo.face(topo.twin(he));
      if (before >= 0) {
        subPointSlot(s.patches_[before], p, topo.to(he)) = gPrev + (1.0 - omega) * lambda;
        ++assigned[before];
      }
    }
  }
  for (int t = 0; t < patchCount; ++t) {
    const auto& q = s.patches_[t];
    const bool finite = q.dw211.allFinite() && q.dv211.allFinite() && q.dw121.allFinite() && q.du121.allFinite() &&
                        q.dv112.allFinite() && q.du112.allFinite();
    if (assigned[t] != 6 || !finite) {
      throw PolyhedronError("patch " + std::to_string(t) + ": expected 6 finite sub-points from the ring solves, got " +
                            std::to_string(assigned[t]) + (finite ? "" : " (non-finite values)"));
    }
  }
  return s;
}

}  // namespace ffdkit::geometry::polyhedron
