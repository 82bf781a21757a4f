// Eigen's dense decompositions that several geometry libraries use, compiled once: each
// declaration below tells a compiling unit that the instance is defined in eigen_instances.cpp
// (ffdkit::geometry_core), so the unit neither instantiates nor optimizes its own copy of these
// out-of-line functions. The same template code runs, only compiled in one place, so results are
// the same to the bit. The geometry libraries include this header before their sources
// (geometry/CMakeLists.txt), so the declarations precede every use in a unity batch. Eigen's
// product and triangular-solve kernels are not declared here: compiled in one place they made
// BM_CurveNetwork/faces:1000 (bench_geometry_polyhedron) 4-10 % and
// BM_ClothoidApproximation/.../errors:1 (bench_geometry_g3) about 6 % slower, for little compile
// time saved.
#pragma once

#include <Eigen/Dense>

#define FFDKIT_EIGEN_DENSE_INSTANCES(EXTERN)                                                      \
  EXTERN template void Eigen::ColPivHouseholderQR<Eigen::MatrixXd>::computeInPlace();            \
  EXTERN template void Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>::computeInPlace(); \
  EXTERN template void Eigen::PartialPivLU<Eigen::MatrixXd>::compute();                          \
  EXTERN template struct Eigen::internal::partial_lu_impl<double, 0, int, -1>;

FFDKIT_EIGEN_DENSE_INSTANCES(extern)
