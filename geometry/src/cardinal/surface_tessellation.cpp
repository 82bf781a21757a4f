#include "ffdkit/geometry/cardinal/surface_tessellation.h"

#include <cmath>

#include <Eigen/Geometry>
#include <string>

#include "ffdkit/geometry/cardinal/cardinal_error.h"

namespace ffdkit::geometry::cardinal {
namespace {

void checkSampling(const SurfaceSampling& sampling) {
  if (sampling.samplesPerSpanU < 1 || sampling.samplesPerSpanV < 1) {
    throw CardinalSplineError("tessellate: samples per span must be >= 1, got " +
                              std::to_string(sampling.samplesPerSpanU) + " x " +
                              std::to_string(sampling.samplesPerSpanV));
  }
}

// Triangles of a (vu x vv) vertex grid; closed directions connect the last column of quads
// back to vertex 0 (the seam is welded).
Eigen::MatrixX3i gridTriangles(int vu, int vv, bool closedU, bool closedV) {
  const int quadsU = closedU ? vu : vu - 1;
  const int quadsV = closedV ? vv : vv - 1;
  Eigen::MatrixX3i tris(2 * quadsU * quadsV, 3);
  int t = 0;
  for (int i = 0; i < quadsU; ++i) {
    const int i1 = (i + 1) % vu;
    for (int j = 0; j < quadsV; ++j) {
      const int j1 = (j + 1) % vv;
      const int a = i * vv + j, b = i1 * vv + j, c = i1 * vv + j1, d = i * vv + j1;
      // Counter-clockwise around Q_u x Q_v: u runs along (a -> b), v along (a -> d).
      tris.row(t++) << a, b, c;
      tris.row(t++) << a, c, d;
    }
  }
  return tris;
}

Eigen::Vector3d unitNormal(const Eigen::Vector3d& du, const Eigen::Vector3d& dv) {
  const Eigen::Vector3d n = du.cross(dv);
  const double len = n.norm();
  return len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

}  // namespace

SurfaceTessellation tessellate(const SigmaSurface& surface, const SurfaceSampling& sampling) {
  checkSampling(sampling);
  surface.validate();
  const SigmaKnots& ku = surface.knotsU;
  const SigmaKnots& kv = surface.knotsV;
  const int su = sampling.samplesPerSpanU, sv = sampling.samplesPerSpanV;
  const int spansU = ku.intervalCount(), spansV = kv.intervalCount();
  const int vu = spansU * su + (ku.closed() ? 0 : 1);
  const int vv = spansV * sv + (kv.closed() ? 0 : 1);
  SurfaceTessellation out;
  out.verticesU = vu;
  out.verticesV = vv;
  out.mesh.vertices.resize(static_cast<Eigen::Index>(vu) * vv, 3);
  out.normals.resize(out.mesh.vertices.rows(), 3);
  out.parameters.resize(out.mesh.vertices.rows(), 2);
  // One patch per span pair, evaluated at all the vertices it owns.
  for (int i = 0; i < spansU; ++i) {
    const int iuEnd = (i == spansU - 1 && !ku.closed()) ? su : su - 1;
    for (int j = 0; j < spansV; ++j) {
      const int ivEnd = (j == spansV - 1 && !kv.closed()) ? sv : sv - 1;
      const QuarticPatch patch = surface.patch(i, j);
      for (int a = 0; a <= iuEnd; ++a) {
        const double s = static_cast<double>(a) / su;
        for (int b = 0; b <= ivEnd; ++b) {
          const double t = static_cast<double>(b) / sv;
          const Eigen::Index row = static_cast<Eigen::Index>(i * su + a) * vv + (j * sv + b);
          out.mesh.vertices.row(row) = evaluateQuarticPatch(patch, s, t).transpose();
          Eigen::Vector3d normal = unitNormal(evaluateQuarticPatch(patch, s, t, 1, 0),
                                              evaluateQuarticPatch(patch, s, t, 0, 1));
          if (normal.isZero()) {
            // Degenerate parametrisation (collapsed edge, pole): take the limit from inside.
            const double inward = 1e-6;
            const double s2 = s + inward * (0.5 - s), t2 = t + inward * (0.5 - t);
            normal = unitNormal(evaluateQuarticPatch(patch, s2, t2, 1, 0),
                                evaluateQuarticPatch(patch, s2, t2, 0, 1));
          }
          out.normals.row(row) = normal.transpose();
          out.parameters.row(row) << ku.knot(i) + s * ku.delta(i), kv.knot(j) + t * kv.delta(j);
        }
      }
    }
  }
  out.mesh.triangles = gridTriangles(vu, vv, ku.closed(), kv.closed());
  return out;
}

SurfaceTessellation tessellate(const SSplineSurface& surface, const SurfaceSampling& sampling) {
  checkSampling(sampling);
  const auto& o = surface.options();
  const int su = sampling.samplesPerSpanU, sv = sampling.samplesPerSpanV;
  const int spansU = static_cast<int>(surface.uEnd()), spansV = static_cast<int>(surface.vEnd());
  const int vu = spansU * su + (o.closedU ? 0 : 1);
  const int vv = spansV * sv + (o.closedV ? 0 : 1);
  SurfaceTessellation out;
  out.verticesU = vu;
  out.verticesV = vv;
  out.mesh.vertices.resize(static_cast<Eigen::Index>(vu) * vv, 3);
  out.normals.resize(out.mesh.vertices.rows(), 3);
  out.parameters.resize(out.mesh.vertices.rows(), 2);
  for (int a = 0; a < vu; ++a) {
    const double u = static_cast<double>(a) / su;
    for (int b = 0; b < vv; ++b) {
      const double v = static_cast<double>(b) / sv;
      const Eigen::Index row = static_cast<Eigen::Index>(a) * vv + b;
      out.mesh.vertices.row(row) = surface.evaluate(u, v).transpose();
      out.normals.row(row) =
          unitNormal(surface.evaluate(u, v, 1, 0), surface.evaluate(u, v, 0, 1)).transpose();
      out.parameters.row(row) << u, v;
    }
  }
  out.mesh.triangles = gridTriangles(vu, vv, o.closedU, o.closedV);
  return out;
}

}  // namespace ffdkit::geometry::cardinal
