#include "ffdkit/geometry/polyhedron/surface_diagnostics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Geometry>

namespace ffdkit::geometry::polyhedron {
namespace {

double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  if (a.squaredNorm() == 0.0 || b.squaredNorm() == 0.0) return std::numbers::pi;
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

Eigen::Vector3d bezier(const std::array<Eigen::Vector3d, 4>& v, double s) {
  const double r = 1.0 - s;
  return r * r * r * v[0] + 3.0 * r * r * s * v[1] + 3.0 * r * s * s * v[2] + s * s * s * v[3];
}

}  // namespace

Eigen::Vector3d edgeBarycentric(const RationalQuarticTriangle& patch, int a, int b, double s) {
  Eigen::Vector3d uvw = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    if (patch.corners[k] == a) uvw[k] = 1.0 - s;
    if (patch.corners[k] == b) uvw[k] = s;
  }
  return uvw;
}

Eigen::Vector3d evaluateOnPatchEdge(const RationalQuarticTriangle& patch, int a, int b, double s) {
  const Eigen::Vector3d uvw = edgeBarycentric(patch, a, b, s);
  return patch.evaluate(uvw[0], uvw[1], uvw[2]);
}

NormalJumpReport maxNormalJump(const PatchSurface& surface, int samplesPerCurve) {
  NormalJumpReport report;
  const MeshTopology& topo = surface.triangulated().topology;
  const auto& patches = surface.patches();
  for (int e = 0; e < topo.edgeCount(); ++e) {
    if (topo.isBoundaryEdge(e)) continue;
    const int he = topo.edgeHalfEdge(e);
    const auto& left = patches[topo.face(he)];
    const auto& right = patches[topo.face(topo.twin(he))];
    const int a = topo.from(he), b = topo.to(he);
    ++report.curvesChecked;
    for (int k = 1; k <= samplesPerCurve; ++k) {
      const double s = static_cast<double>(k) / (samplesPerCurve + 1);
      const Eigen::Vector3d l = edgeBarycentric(left, a, b, s), r = edgeBarycentric(right, a, b, s);
      const Eigen::Vector3d nl = left.normal(l[0], l[1], l[2]), nr = right.normal(r[0], r[1], r[2]);
      const double angle = angleBetween(nl, nr);
      report.minCosine = std::min(report.minCosine, nl.dot(nr));
      if (!(angle <= report.maxAngle)) {
        report.maxAngle = angle;
        report.worstHalfEdge = he;
      }
    }
  }
  return report;
}

double maxBoundaryDeviation(const PatchSurface& surface, int samples) {
  double worst = 0.0;
  const auto& points = surface.triangulated().points;
  for (const auto& patch : surface.patches()) {
    for (int k = 0; k < 3; ++k) {
      const int a = patch.corners[k], b = patch.corners[(k + 1) % 3];
      const auto cubic = surface.curve(a, b);
      for (int j = 0; j <= samples; ++j) {
        const double s = static_cast<double>(j) / samples;
        const double d = (evaluateOnPatchEdge(patch, a, b, s) - bezier(cubic, s)).norm();
        worst = std::max(worst, std::isfinite(d) ? d : std::numeric_limits<double>::infinity());
      }
      worst = std::max(worst, (evaluateOnPatchEdge(patch, a, b, 0.0) - points.row(a).transpose()).norm());
    }
  }
  return worst;
}

double maxCornerNormalDeviation(const PatchSurface& surface) {
  double worst = 0.0;
  const auto& net = surface.triangulated();
  for (const auto& patch : surface.patches()) {
    for (int k = 0; k < 3; ++k) {
      const int p = patch.corners[k];
      const auto& ring = net.topology.ringHalfEdges(p);
      const Eigen::Vector3d planeNormal = net.legs.row(ring[0]).cross(net.legs.row(ring[1])).transpose();
      Eigen::Vector3d uvw = Eigen::Vector3d::Zero();
      uvw[k] = 1.0;
      worst = std::max(worst, angleBetween(patch.normal(uvw[0], uvw[1], uvw[2]), planeNormal));
    }
  }
  return worst;
}

}  // namespace ffdkit::geometry::polyhedron
