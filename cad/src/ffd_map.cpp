#include "ffd_map.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/SVD>
#include <Geom_BSplineSurface.hxx>

#include "ffdkit/cad/cad_error.h"
#include "ffdkit/ffd/deformer.h"
#include "ffdkit/ffd/embedding.h"

namespace ffdkit::cad {

FfdMap::FfdMap(const ffd::Lattice& lattice, const CadDeformOptions& options, double modelSize)
    : lattice_(lattice), extended_(lattice), options_(options) {
  extended_.setOutsidePolicy(ffd::OutsidePolicy::extrapolate());
  if (options.method == CadMethod::Exact &&
      (options.maxDegree < 1 || options.maxDegree > Geom_BSplineSurface::MaxDegree()))
    throw CadError("maxDegree must be in [1, " + std::to_string(Geom_BSplineSurface::MaxDegree()) + "], got " +
                   std::to_string(options.maxDegree));
  if (!(options.tolerance >= 0.0) || !std::isfinite(options.tolerance))
    throw CadError("the approximation tolerance must be >= 0 and finite, got " + std::to_string(options.tolerance));
  tolerance_ = options.tolerance > 0.0 ? options.tolerance : 1e-6 * std::max(modelSize, 1e-300);
  polynomial_ = lattice.restIsAffine() && !lattice.axis(0).periodic() && !lattice.axis(1).periodic() &&
                !lattice.axis(2).periodic();
  if (options.method == CadMethod::Exact && !polynomial_ && !options.approximate)
    throw CadError("exact CAD deformation needs a lattice whose rest shape is a box (an affine rest map and no "
                   "periodic axis): the FFD of a cylindrical lattice is not a polynomial of world coordinates; allow "
                   "the approximation to deform with it");
  if (polynomial_) {
    Eigen::Affine3d toLocalParameter = Eigen::Affine3d::Identity();
    toLocalParameter.linear() = lattice.restAffineLinear().inverse();
    toLocalParameter.translation() = -(toLocalParameter.linear() * lattice.restAffineOffset());
    toParameter_ = toLocalParameter * lattice.frame().inverse();
    for (int a = 0; a < 3; ++a)
      for (int cell = 1; cell < lattice.axis(a).cellCount(); ++cell) planes_[a].push_back(lattice.axis(a).cellMin(cell));
    for (int a = 0; a < 3; ++a) {
      kinks_[a] = planes_[a];
      if (!extrapolates()) {
        kinks_[a].push_back(lattice.axis(a).domainMin());
        kinks_[a].push_back(lattice.axis(a).domainMax());
      }
    }
    lipschitz_ = lipschitzBound();
  } else {
    lipschitz_ = 1.0;  // edges' and vertices' tolerances are measured after the approximation
  }
}

bool FfdMap::inside(const Eigen::Vector3d& world) const {
  const Eigen::Vector3d uvw = parameters(world);
  const Eigen::Vector3d lo = lattice_.parameterMin(), hi = lattice_.parameterMax();
  const Eigen::Vector3d eps = 1e-9 * (hi - lo);
  return (uvw.array() >= (lo - eps).array()).all() && (uvw.array() <= (hi + eps).array()).all();
}

const BernsteinVolume& FfdMap::cellVolume(const Eigen::Vector3i& cell) const {
  const std::array<int, 3> key{cell[0], cell[1], cell[2]};
  auto found = cells_.find(key);
  if (found == cells_.end()) found = cells_.emplace(key, BernsteinVolume::fromLatticeCell(lattice_, cell)).first;
  return found->second;
}

Eigen::MatrixX3d FfdMap::points(const Eigen::MatrixX3d& world, bool extend) const {
  if (world.rows() == 0) return world;
  const ffd::Lattice& lattice = extend && polynomial_ ? extended_ : lattice_;
  ffd::EmbedOptions embedOptions;
  embedOptions.parallel = world.rows() > 20000;
  ffd::Deformer deformer(ffd::embed(lattice, world, embedOptions));
  deformer.setParallel(embedOptions.parallel);
  return deformer.deform(lattice, world);
}

Eigen::Vector3d FfdMap::point(const Eigen::Vector3d& world) const {
  const Eigen::MatrixX3d one = world.transpose();
  return points(one).row(0).transpose();
}

double FfdMap::lipschitzBound() const {
  // |J v| <= |R|_2 sqrt(sum_a c_a^2) |v|, R = d(uvw)/dq, c_a a bound of |dX/du_a| (the
  // derivative's control net: degree times the largest difference of neighbours along a).
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  const Eigen::Vector3i n = lattice_.counts();
  const Eigen::MatrixX3d world = (lattice_.frame() * lattice_.controlPoints().transpose()).transpose();
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const Eigen::Index at = lattice_.index(i, j, k);
        if (i + 1 < n[0]) c[0] = std::max(c[0], (world.row(lattice_.index(i + 1, j, k)) - world.row(at)).norm());
        if (j + 1 < n[1]) c[1] = std::max(c[1], (world.row(lattice_.index(i, j + 1, k)) - world.row(at)).norm());
        if (k + 1 < n[2]) c[2] = std::max(c[2], (world.row(lattice_.index(i, j, k + 1)) - world.row(at)).norm());
      }
  for (int a = 0; a < 3; ++a) {
    const auto& axis = lattice_.axis(a);
    const double span = axis.domainMax() - axis.domainMin();
    // A B-spline's derivative net divides by knot spans; degree / (smallest cell) bounds it.
    double smallest = span;
    for (int cell = 0; cell < axis.cellCount(); ++cell) smallest = std::min(smallest, axis.cellMax(cell) - axis.cellMin(cell));
    c[a] *= axis.degree() / smallest;
  }
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(toParameter_.linear());
  return svd.singularValues()[0] * c.norm();
}

}  // namespace ffdkit::cad
