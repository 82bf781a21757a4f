#include "ffdkit/widgets/cell.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include <Eigen/SVD>

#include "ffdkit/widgets/widget_error.h"

namespace ffdkit::widgets {
namespace {

[[noreturn]] void invalid(const std::string& message) {
  throw WidgetError(WidgetErrorCode::InvalidArgument, message);
}

std::string str(const Eigen::Vector3i& v) {
  std::ostringstream os;
  os << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return os.str();
}

Eigen::Index flat(const Eigen::Vector3i& counts, int i, int j, int k) {
  return i + static_cast<Eigen::Index>(counts.x()) * (j + static_cast<Eigen::Index>(counts.y()) * k);
}

void checkAxis(int axis, std::string_view what) {
  if (axis < 0 || axis > 2) invalid(std::string(what) + " axis must be 0, 1 or 2, got " + std::to_string(axis));
}

// Orthonormal frame with x along `xdir` and y in the plane of (xdir, ydir); falls back to a
// lattice axis when ydir is (nearly) parallel to xdir.
Eigen::Matrix3d frameFrom(const Eigen::Vector3d& xdir, const Eigen::Vector3d& ydir) {
  Eigen::Vector3d x = xdir.norm() > 0 ? xdir.normalized() : Eigen::Vector3d::UnitX();
  Eigen::Vector3d y = ydir - ydir.dot(x) * x;
  if (y.norm() <= 1e-12 * std::max(1.0, ydir.norm())) {
    Eigen::Index minAxis;
    x.cwiseAbs().minCoeff(&minAxis);
    Eigen::Vector3d e = Eigen::Vector3d::Unit(minAxis);
    y = e - e.dot(x) * x;
  }
  y.normalize();
  Eigen::Matrix3d r;
  r.col(0) = x;
  r.col(1) = y;
  r.col(2) = x.cross(y);
  return r;
}

}  // namespace

std::string_view cellKindName(CellKind kind) {
  switch (kind) {
    case CellKind::Point: return "point";
    case CellKind::Edge: return "edge";
    case CellKind::Face: return "face";
    case CellKind::Slab: return "slab";
    case CellKind::Box: return "box";
    case CellKind::Custom: return "custom";
  }
  return "unknown";
}

std::optional<CellKind> parseCellKind(std::string_view name) {
  for (CellKind k : {CellKind::Point, CellKind::Edge, CellKind::Face, CellKind::Slab, CellKind::Box,
                     CellKind::Custom}) {
    if (cellKindName(k) == name) return k;
  }
  return std::nullopt;
}

AffineMask defaultAttachmentMask(CellKind kind) {
  return (kind == CellKind::Point || kind == CellKind::Custom) ? AffineMask::t() : AffineMask::tr();
}

CellSpec CellSpec::point(int i, int j, int k) { return {CellKind::Point, {i, j, k}, 0, {}}; }
CellSpec CellSpec::edge(int i, int j, int k, int alongAxis) { return {CellKind::Edge, {i, j, k}, alongAxis, {}}; }
CellSpec CellSpec::face(int i, int j, int k, int normalAxis) { return {CellKind::Face, {i, j, k}, normalAxis, {}}; }
CellSpec CellSpec::slab(int normalAxis, int planeIndex) {
  CellSpec s{CellKind::Slab, Eigen::Vector3i::Zero(), normalAxis, {}};
  if (normalAxis >= 0 && normalAxis <= 2) s.base[normalAxis] = planeIndex;
  return s;
}
CellSpec CellSpec::box(int i, int j, int k) { return {CellKind::Box, {i, j, k}, 0, {}}; }
CellSpec CellSpec::custom(std::vector<Eigen::Index> flatIndices) {
  return {CellKind::Custom, Eigen::Vector3i::Zero(), 0, std::move(flatIndices)};
}

std::vector<Eigen::Index> cellPointIndices(const Eigen::Vector3i& counts, const CellSpec& spec) {
  if ((counts.array() < 2).any()) invalid("lattice needs >= 2 points per axis, got " + str(counts));
  const Eigen::Vector3i& b = spec.base;
  // Extent of the cell in grid steps along each axis, to check it stays inside the grid.
  Eigen::Vector3i extent = Eigen::Vector3i::Zero();
  switch (spec.kind) {
    case CellKind::Point: break;
    case CellKind::Edge:
      checkAxis(spec.axis, "edge");
      extent[spec.axis] = 1;
      break;
    case CellKind::Face:
      checkAxis(spec.axis, "face normal");
      extent.setOnes();
      extent[spec.axis] = 0;
      break;
    case CellKind::Box: extent.setOnes(); break;
    case CellKind::Slab: {
      checkAxis(spec.axis, "slab normal");
      int p = b[spec.axis];
      if (p < 0 || p >= counts[spec.axis])
        invalid("slab plane index " + std::to_string(p) + " outside [0, " +
                std::to_string(counts[spec.axis] - 1) + "] on axis " + std::to_string(spec.axis));
      break;
    }
    case CellKind::Custom: {
      if (spec.indices.empty()) invalid("custom cell needs at least one point");
      const Eigen::Index n = static_cast<Eigen::Index>(counts.prod());
      std::set<Eigen::Index> seen;
      for (Eigen::Index i : spec.indices) {
        if (i < 0 || i >= n)
          invalid("custom cell point " + std::to_string(i) + " outside [0, " + std::to_string(n - 1) + "]");
        if (!seen.insert(i).second) invalid("custom cell lists point " + std::to_string(i) + " twice");
      }
      return spec.indices;
    }
  }
  if (spec.kind != CellKind::Slab) {
    for (int a = 0; a < 3; ++a) {
      if (b[a] < 0 || b[a] + extent[a] >= counts[a])
        invalid(std::string(cellKindName(spec.kind)) + " cell at " + str(b) +
                " does not fit a lattice of counts " + str(counts));
    }
  }
  std::vector<Eigen::Index> out;
  switch (spec.kind) {
    case CellKind::Point: out.push_back(flat(counts, b.x(), b.y(), b.z())); break;
    case CellKind::Edge: {
      Eigen::Vector3i e = b;
      e[spec.axis] += 1;
      out = {flat(counts, b.x(), b.y(), b.z()), flat(counts, e.x(), e.y(), e.z())};
      break;
    }
    case CellKind::Face: {
      const int a = (spec.axis + 1) % 3, c = (spec.axis + 2) % 3;
      for (auto [da, dc] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}}) {
        Eigen::Vector3i p = b;
        p[a] += da;
        p[c] += dc;
        out.push_back(flat(counts, p.x(), p.y(), p.z()));
      }
      break;
    }
    case CellKind::Slab: {
      const int a = (spec.axis + 1) % 3, c = (spec.axis + 2) % 3;
      Eigen::Vector3i p = Eigen::Vector3i::Zero();
      p[spec.axis] = b[spec.axis];
      for (int ic = 0; ic < counts[c]; ++ic) {
        for (int ia = 0; ia < counts[a]; ++ia) {
          p[a] = ia;
          p[c] = ic;
          out.push_back(flat(counts, p.x(), p.y(), p.z()));
        }
      }
      break;
    }
    case CellKind::Box:
      for (int dk = 0; dk < 2; ++dk)
        for (int dj = 0; dj < 2; ++dj)
          for (int di = 0; di < 2; ++di) out.push_back(flat(counts, b.x() + di, b.y() + dj, b.z() + dk));
      break;
    case CellKind::Custom: break;
  }
  return out;
}

Eigen::Isometry3d cellRestFrame(const CellSpec& spec, const Eigen::Vector3i& counts,
                                const Eigen::Ref<const Eigen::MatrixX3d>& p) {
  Eigen::Isometry3d f = Eigen::Isometry3d::Identity();
  f.translation() = p.colwise().mean().transpose();
  auto row = [&](Eigen::Index r) -> Eigen::Vector3d { return p.row(r).transpose(); };
  switch (spec.kind) {
    case CellKind::Point:
    case CellKind::Custom: break;
    case CellKind::Edge: {
      // y from the next lattice axis, so an axis-aligned edge gets a cyclic permutation of them.
      f.linear() = frameFrom(row(1) - row(0), Eigen::Vector3d::Unit((spec.axis + 1) % 3));
      break;
    }
    case CellKind::Face:
      f.linear() = frameFrom((row(1) - row(0)) + (row(2) - row(3)), (row(3) - row(0)) + (row(2) - row(1)));
      break;
    case CellKind::Slab: {
      const int na = counts[(spec.axis + 1) % 3], nc = counts[(spec.axis + 2) % 3];
      Eigen::Vector3d xdir = Eigen::Vector3d::Zero(), ydir = Eigen::Vector3d::Zero();
      for (int ic = 0; ic < nc; ++ic) xdir += row(ic * na + na - 1) - row(ic * na);
      for (int ia = 0; ia < na; ++ia) ydir += row((nc - 1) * na + ia) - row(ia);
      // A grid direction that closes on itself (the angular rings of a cylindrical lattice) sums
      // to ~0, and a frame built from it followed round-off: a ring's rotate widget could turn
      // either way. Then z is the slab's grid normal (the sum of its quads' diagonal cross
      // products, oriented like a -> c) and x the lattice x axis in the slab's plane.
      double extent = 0.0;
      for (Eigen::Index r = 1; r < p.rows(); ++r) extent = std::max(extent, (row(r) - row(0)).norm());
      const double tiny = 1e-9 * extent * std::max(na, nc);
      if (xdir.norm() <= tiny || ydir.norm() <= tiny) {
        Eigen::Vector3d n = Eigen::Vector3d::Zero();
        for (int ic = 0; ic + 1 < nc; ++ic)
          for (int ia = 0; ia + 1 < na; ++ia) {
            const Eigen::Index r = ic * na + ia;
            n += (row(r + na + 1) - row(r)).cross(row(r + na) - row(r + 1));
          }
        const Eigen::Vector3d z = n.norm() > 0.0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Unit(spec.axis);
        Eigen::Vector3d x = Eigen::Vector3d::UnitX() - z.x() * z;
        if (x.norm() < 1e-6) x = Eigen::Vector3d::UnitY() - z.y() * z;
        f.linear() = frameFrom(x, z.cross(x));
        break;
      }
      f.linear() = frameFrom(xdir, ydir);
      break;
    }
    case CellKind::Box: {
      Eigen::Vector3d xdir = Eigen::Vector3d::Zero(), ydir = Eigen::Vector3d::Zero();
      for (int r = 0; r < 8; r += 2) xdir += row(r + 1) - row(r);
      for (int r : {0, 1, 4, 5}) ydir += row(r + 2) - row(r);
      f.linear() = frameFrom(xdir, ydir);
      break;
    }
  }
  return f;
}

Eigen::Affine3d CellAffine::matrix(const Eigen::Isometry3d& restFrame, AffineMask mask) const {
  const Eigen::Vector3d c = restFrame.translation();
  const Eigen::Matrix3d e = restFrame.linear();
  Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
  if (mask.rotate) linear = rotation;
  if (mask.scale) linear = linear * e * scale.asDiagonal() * e.transpose();
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  a.linear() = linear;
  a.translation() = c + (mask.translate ? translation : Eigen::Vector3d::Zero()) - linear * c;
  return a;
}

CellAffine fitCellAffine(const CellSpec& spec, const Eigen::Isometry3d& restFrame,
                         const Eigen::Ref<const Eigen::MatrixX3d>& rest,
                         const Eigen::Ref<const Eigen::MatrixX3d>& current) {
  CellAffine fit;
  const Eigen::RowVector3d restCentroid = rest.colwise().mean();
  const Eigen::RowVector3d centroid = current.colwise().mean();
  fit.translation = (centroid - restCentroid).transpose();
  if (spec.kind == CellKind::Point || rest.rows() < 2) return fit;
  const Eigen::Matrix3d e = restFrame.linear();
  if (spec.kind == CellKind::Edge) {
    const Eigen::Vector3d d0 = (rest.row(1) - rest.row(0)).transpose();
    const Eigen::Vector3d d = (current.row(1) - current.row(0)).transpose();
    if (d0.norm() > 0 && d.norm() > 0) {
      fit.rotation = Eigen::Quaterniond::FromTwoVectors(d0, d).toRotationMatrix();
      fit.scale.x() = d.norm() / d0.norm();
    }
    return fit;
  }
  const Eigen::MatrixX3d q = rest.rowwise() - restCentroid;
  const Eigen::MatrixX3d r = current.rowwise() - centroid;
  const Eigen::Matrix3d h = q.transpose() * r;  // sum q_i r_i^T
  const double size = q.squaredNorm();
  if (size <= 0.0) return fit;
  if (h.norm() > 1e-14 * size) {
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
    d(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
    fit.rotation = svd.matrixV() * d * svd.matrixU().transpose();
  }
  // Per-axis least squares in the cell's axes: r_a ≈ s_a q_a after undoing the rotation.
  const Eigen::MatrixX3d qc = q * e;
  const Eigen::MatrixX3d rc = r * fit.rotation * e;  // rows: (R^T r_i)^T E = r_i^T R E
  for (int a = 0; a < 3; ++a) {
    const double qq = qc.col(a).squaredNorm();
    if (qq > 1e-20 * size) fit.scale[a] = qc.col(a).dot(rc.col(a)) / qq;
  }
  return fit;
}

}  // namespace ffdkit::widgets
