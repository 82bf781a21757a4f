#include "ffdkit/geometry/cardinal/surface_tessellation.h"

#include <array>
#include <cmath>
#include <string>
#include <utility>

#include <Eigen/Geometry>

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
  // Quartic Bernstein values and derivatives at the local sample parameters, shared by all
  // patches; then one patch per span pair, evaluated at all the vertices it owns.
  const auto table = [](int samples) {
    Eigen::MatrixXd value(samples + 1, 5), slope(samples + 1, 5);
    for (int a = 0; a <= samples; ++a) {
      const double s = static_cast<double>(a) / samples, r = 1.0 - s;
      const double b3[4] = {r * r * r, 3 * s * r * r, 3 * s * s * r, s * s * s};
      const double binom[5] = {1, 4, 6, 4, 1};
      for (int k = 0; k <= 4; ++k) {
        value(a, k) = binom[k] * std::pow(s, k) * std::pow(r, 4 - k);
        // d/ds B^4_k = 4 (B^3_{k-1} - B^3_k)
        slope(a, k) = 4.0 * ((k > 0 ? b3[k - 1] : 0.0) - (k < 4 ? b3[k] : 0.0));
      }
    }
    return std::pair{value, slope};
  };
  const auto [bu, dbu] = table(su);
  const auto [bv, dbv] = table(sv);
  std::array<Eigen::Vector3d, 5> c, dc;
  for (int i = 0; i < spansU; ++i) {
    const int iuEnd = (i == spansU - 1 && !ku.closed()) ? su : su - 1;
    for (int j = 0; j < spansV; ++j) {
      const int ivEnd = (j == spansV - 1 && !kv.closed()) ? sv : sv - 1;
      const QuarticPatch patch = surface.patch(i, j);
      for (int a = 0; a <= iuEnd; ++a) {
        for (int l = 0; l <= 4; ++l) {
          c[l].setZero();
          dc[l].setZero();
          for (int k = 0; k <= 4; ++k) {
            c[l] += bu(a, k) * patch[k][l];
            dc[l] += dbu(a, k) * patch[k][l];
          }
        }
        for (int b = 0; b <= ivEnd; ++b) {
          Eigen::Vector3d p = Eigen::Vector3d::Zero(), pu = p, pv = p;
          for (int l = 0; l <= 4; ++l) {
            p += bv(b, l) * c[l];
            pu += bv(b, l) * dc[l];
            pv += dbv(b, l) * c[l];
          }
          const Eigen::Index row = static_cast<Eigen::Index>(i * su + a) * vv + (j * sv + b);
          out.mesh.vertices.row(row) = p.transpose();
          Eigen::Vector3d normal = unitNormal(pu, pv);
          if (normal.isZero()) {
            // Degenerate parametrisation (collapsed edge, pole): take the limit from inside.
            const double s = static_cast<double>(a) / su, t = static_cast<double>(b) / sv;
            const double inward = 1e-6;
            const double s2 = s + inward * (0.5 - s), t2 = t + inward * (0.5 - t);
            normal = unitNormal(evaluateQuarticPatch(patch, s2, t2, 1, 0),
                                evaluateQuarticPatch(patch, s2, t2, 0, 1));
          }
          out.normals.row(row) = normal.transpose();
          out.parameters.row(row) << ku.knot(i) + ku.delta(i) * a / su,
              kv.knot(j) + kv.delta(j) * b / sv;
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
  Eigen::VectorXd us(vu), vs(vv);
  for (int a = 0; a < vu; ++a) us[a] = static_cast<double>(a) / su;
  for (int b = 0; b < vv; ++b) vs[b] = static_cast<double>(b) / sv;
  SSplineSurface::GridSamples g = surface.sampleGrid(us, vs);
  SurfaceTessellation out;
  out.verticesU = vu;
  out.verticesV = vv;
  out.mesh.vertices = std::move(g.points);
  out.normals.resize(out.mesh.vertices.rows(), 3);
  out.parameters.resize(out.mesh.vertices.rows(), 2);
  for (int a = 0; a < vu; ++a) {
    for (int b = 0; b < vv; ++b) {
      const Eigen::Index row = static_cast<Eigen::Index>(a) * vv + b;
      out.normals.row(row) =
          unitNormal(g.du.row(row).transpose(), g.dv.row(row).transpose()).transpose();
      out.parameters.row(row) << us[a], vs[b];
    }
  }
  out.mesh.triangles = gridTriangles(vu, vv, o.closedU, o.closedV);
  return out;
}

}  // namespace ffdkit::geometry::cardinal
