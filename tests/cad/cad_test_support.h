#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>
#include <unistd.h>

#include "ffdkit/cad/cad_model.h"
#include "ffdkit/cad/tessellation.h"
#include "ffdkit/ffd/box_lattice_options.h"
#include "ffdkit/ffd/cylindrical_lattice.h"
#include "ffdkit/ffd/deformer.h"
#include "ffdkit/ffd/embedding.h"
#include "ffdkit/ffd/lattice.h"

namespace ffdkit::cad::test {

/// A Bernstein box lattice around `box` (grown by 5% of its size on every side) with its control
/// points displaced smoothly: a bend along x, a bulge in y and a twist-like shear in z, each up to
/// `amount` x the box diagonal, and a widening towards the top (which changes the volume). counts = control points per axis.
/// `basis`: the basis of every axis (Bernstein by default).
inline ffd::Lattice deformedLatticeAround(const Eigen::AlignedBox3d& box, const Eigen::Vector3i& counts, double amount,
                                          const ffd::AxisBasis& basis = ffd::AxisBasis::bernstein()) {
  ffd::BoxLatticeOptions options;
  options.counts = counts;
  options.bases = {basis, basis, basis};
  const Eigen::Vector3d pad = 0.05 * box.sizes();
  options.boxMin = box.min() - pad;
  options.boxMax = box.max() + pad;
  ffd::Lattice lattice = ffd::makeBoxLattice(options);
  Eigen::MatrixX3d points = lattice.restPoints();
  const double size = amount * box.diagonal().norm();
  for (int k = 0; k < counts[2]; ++k)
    for (int j = 0; j < counts[1]; ++j)
      for (int i = 0; i < counts[0]; ++i) {
        const double u = double(i) / (counts[0] - 1), v = double(j) / (counts[1] - 1), w = double(k) / (counts[2] - 1);
        const Eigen::Index at = lattice.index(i, j, k);
        points(at, 0) += size * (w * w - 0.3 * v + 1.5 * (u - 0.5) * w);
        points(at, 1) += size * (0.5 * std::sin(3.0 * u + 1.0) + (v - 0.5)) * w;
        points(at, 2) += size * 0.4 * (u - 0.5) * (v - 0.5);
      }
  lattice.setControlPoints(points);
  return lattice;
}

/// A cylindrical (EFFD) lattice of 3 x 8 x 3 points with quadratic axes around the model, its axis
/// along z through the centre of its bounding box, of radius `radiusFactor` x the box's xy
/// diagonal, 2 beyond its bottom and top; its rings widened towards the top and leaning along y
/// (the rest lattice is no identity either: its B-spline rings lie inside their control points).
inline ffd::Lattice cylinderAround(const CadModel& model, double radiusFactor = 0.75) {
  const Eigen::AlignedBox3d box = model.bounds();
  ffd::CylindricalLatticeOptions cylinder;
  cylinder.counts = {3, 8, 3};
  cylinder.bases = {ffd::AxisBasis::bspline(2), ffd::AxisBasis::periodic(2), ffd::AxisBasis::bspline(2)};
  cylinder.outerRadius = radiusFactor * box.sizes().head<2>().norm();
  cylinder.zMin = box.min().z() - 2.0;
  cylinder.zMax = box.max().z() + 2.0;
  cylinder.frame = Eigen::Translation3d(box.center().x(), box.center().y(), 0.0);
  ffd::Lattice lattice = ffd::makeCylindricalLattice(cylinder);
  Eigen::MatrixX3d points = lattice.restPoints();
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double height = (points(i, 2) - cylinder.zMin) / (cylinder.zMax - cylinder.zMin);
    points(i, 0) *= 1.0 + 0.1 * height;
    points(i, 1) += 0.05 * points(i, 2);
  }
  lattice.setControlPoints(points);
  return lattice;
}

/// The lattice's FFD of world points (rows) through the engine's own evaluation (Lattice::evaluate
/// on the affine rest map's parameters), independent of the composition code; the frame's and the
/// rest map's inverses computed once for all points.
inline Eigen::MatrixX3d ffdOfRows(const ffd::Lattice& lattice, const Eigen::MatrixX3d& world) {
  const auto toLocal = lattice.frame().inverse();
  const Eigen::Matrix3d toParameters = lattice.restAffineLinear().inverse();
  Eigen::MatrixX3d moved(world.rows(), 3);
  for (Eigen::Index i = 0; i < world.rows(); ++i) {
    const Eigen::Vector3d local = toLocal * Eigen::Vector3d(world.row(i).transpose());
    const Eigen::Vector3d uvw = toParameters * (local - lattice.restAffineOffset());
    moved.row(i) = (lattice.frame() * lattice.evaluate(uvw)).transpose();
  }
  return moved;
}

/// ffdOfRows of one point.
inline Eigen::Vector3d ffdOf(const ffd::Lattice& lattice, const Eigen::Vector3d& world) {
  return ffdOfRows(lattice, world.transpose()).row(0).transpose();
}

/// The FFD of world points as the engine deforms a mesh (embed, then Deformer::deform), the
/// lattice's outside policy applied: what ClampEdge and Falloff do outside the lattice.
inline Eigen::MatrixX3d engineFfd(const ffd::Lattice& lattice, const Eigen::MatrixX3d& world) {
  ffd::Deformer deformer(ffd::embed(lattice, world));
  return deformer.deform(lattice, world);
}

/// Triangle t's corners a, b, c.
inline std::array<Eigen::Vector3d, 3> triangleCorners(const CadTriangles& mesh, Eigen::Index t) {
  return {mesh.points.row(mesh.triangles(t, 0)).transpose(), mesh.points.row(mesh.triangles(t, 1)).transpose(),
          mesh.points.row(mesh.triangles(t, 2)).transpose()};
}

/// The sides n = 2^k of each triangle's split into 4^k flat triangles at h: k = log2 of its longest
/// edge / h, at most 6.
inline std::vector<int> splitSides(const CadTriangles& mesh, double h) {
  std::vector<int> sides;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    const auto [a, b, c] = triangleCorners(mesh, t);
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    sides.push_back(1 << std::clamp(static_cast<int>(std::ceil(std::log2(std::max(longest / h, 1.0)))), 0, 6));
  }
  return sides;
}

/// The corners (i, j), 0 <= i, i + j <= n = sides[t], of each triangle a, b, c's split, at
/// a + (b - a) i / n + (c - a) j / n: triangle after triangle, i-major.
inline Eigen::MatrixX3d splitCorners(const CadTriangles& mesh, const std::vector<int>& sides) {
  std::vector<Eigen::Vector3d> corners;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    const auto [a, b, c] = triangleCorners(mesh, t);
    const int n = sides[static_cast<std::size_t>(t)];
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) corners.push_back(a + (b - a) * double(i) / n + (c - a) * double(j) / n);
  }
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(corners.size()), 3);
  for (std::size_t i = 0; i < corners.size(); ++i) points.row(static_cast<Eigen::Index>(i)) = corners[i].transpose();
  return points;
}

/// The volume enclosed by the splits of sides `sides` of a closed triangle set, their corners
/// read from `moved`: the moved corners of splits of sides `movedSides`, each a multiple m = s n
/// of the triangle's n, whose corner (s i, s j) is (i, j) ((b - a) i / n and (b - a) s i / s n are the
/// same doubles: s is a power of 2).
inline double splitVolume(const std::vector<int>& sides, const std::vector<int>& movedSides, const Eigen::MatrixX3d& moved) {
  double volume = 0.0;
  Eigen::Index base = 0;
  for (std::size_t t = 0; t < sides.size(); ++t) {
    const int n = sides[t], m = movedSides[t], s = m / n;
    EXPECT_EQ(m % n, 0);
    // Row of (i, j) in the triangle's block of side m: sum_{i' < i} (m + 1 - i') + j.
    auto at = [&](int i, int j) -> Eigen::Vector3d {
      const Eigen::Index row = s * i, column = s * j;
      return moved.row(base + row * (m + 1) - row * (row - 1) / 2 + column).transpose();
    };
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        const Eigen::Vector3d p = at(i, j), q = at(i + 1, j), r = at(i, j + 1);
        volume += p.dot(q.cross(r)) / 6.0;
        if (i + j + 2 <= n) {
          const Eigen::Vector3d u = at(i + 1, j + 1);
          volume += q.dot(u.cross(r)) / 6.0;
        }
      }
    base += static_cast<Eigen::Index>(m + 1) * (m + 2) / 2;
  }
  return volume;
}

/// The area of the triangles with their points mapped by `map`.
template <class Map>
double mappedArea(const CadTriangles& mesh, Map&& map) {
  const Eigen::MatrixX3d moved = map(mesh.points);
  double area = 0.0;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    const Eigen::Vector3d a = moved.row(mesh.triangles(t, 0)), b = moved.row(mesh.triangles(t, 1)),
                          c = moved.row(mesh.triangles(t, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

/// The volume of a deformed tessellation, its estimated error and its area.
struct TessellatedVolume {
  double volume = 0.0;  ///< of the tessellation refined to triangles shorter than 1% of the size
  double error = 0.0;   ///< from the difference to the 2% refinement (chord error ~ h^2) and the deflection
  double area = 0.0;    ///< of the deformed triangles
};

/// The volume of the model deformed by `map` from its fine tessellation (deflection 3e-5 x size),
/// its triangles split at h = 2% and 1% of the size: a side at 2% is the side at 1% or half of it
/// (k one less), so the points of the 1% splits, mapped once, serve both.
template <class Map>
TessellatedVolume deformedTessellationVolume(const CadModel& model, Map&& map) {
  const double size = model.bounds().diagonal().norm();
  TessellationOptions fine;
  fine.linearDeflection = 3e-5 * size;
  const CadTriangles mesh = tessellate(model, fine);
  const std::vector<int> coarseSides = splitSides(mesh, 0.02 * size), finerSides = splitSides(mesh, 0.01 * size);
  const Eigen::MatrixX3d moved = map(splitCorners(mesh, finerSides));
  const double coarse = splitVolume(coarseSides, finerSides, moved);
  const double finer = splitVolume(finerSides, finerSides, moved);
  const double area = mappedArea(mesh, map);
  return {finer, std::abs(coarse - finer) / 3.0 + area * fine.linearDeflection, area};
}

}  // namespace ffdkit::cad::test

namespace ffdkit::cad::test {

/// A fresh folder for one test's files (removed when it goes).
class ScratchFolder {
 public:
  ScratchFolder() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("ffdkit-cad-" + std::string(info->name()) + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace ffdkit::cad::test
