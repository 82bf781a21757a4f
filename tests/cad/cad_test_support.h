#pragma once

#include <cmath>
#include <filesystem>
#include <string>

#include <Eigen/Core>
#include <gtest/gtest.h>
#include <unistd.h>

#include "ffdkit/cad/cad_model.h"
#include "ffdkit/ffd/box_lattice_options.h"
#include "ffdkit/ffd/lattice.h"

namespace ffdkit::cad::test {

/// A Bernstein box lattice around `box` (grown by 5% of its size on every side) with its control
/// points displaced smoothly: a bend along x, a bulge in y and a twist-like shear in z, each up to
/// `amount` x the box diagonal, and a widening towards the top (which changes the volume). counts = control points per axis.
inline ffd::Lattice deformedLatticeAround(const Eigen::AlignedBox3d& box, const Eigen::Vector3i& counts, double amount) {
  ffd::BoxLatticeOptions options;
  options.counts = counts;
  options.bases = {ffd::AxisBasis::bernstein(), ffd::AxisBasis::bernstein(), ffd::AxisBasis::bernstein()};
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

/// The lattice's FFD of a world point through the engine's own evaluation (Lattice::evaluate on the
/// affine rest map's parameters), independent of the composition code.
inline Eigen::Vector3d ffdOf(const ffd::Lattice& lattice, const Eigen::Vector3d& world) {
  const Eigen::Vector3d local = lattice.frame().inverse() * world;
  const Eigen::Vector3d uvw = lattice.restAffineLinear().inverse() * (local - lattice.restAffineOffset());
  return lattice.frame() * lattice.evaluate(uvw);
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
