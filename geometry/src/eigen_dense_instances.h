// Eigen's dense decompositions and product kernels that several geometry libraries use, compiled
// once: each declaration below tells a compiling unit that the instance is defined in
// eigen_instances.cpp (ffdkit::geometry_core), so the unit neither instantiates nor optimizes its
// own copy of these out-of-line functions. The same template code runs, only compiled in one
// place, so results are the same to the bit. The geometry libraries include this header before
// their sources (geometry/CMakeLists.txt), so the declarations precede every use in a unity batch.
#pragma once

#include <Eigen/Dense>

#define FFDKIT_EIGEN_DENSE_INSTANCES(EXTERN)                                                      \
  EXTERN template void Eigen::ColPivHouseholderQR<Eigen::MatrixXd>::computeInPlace();            \
  EXTERN template void Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>::computeInPlace(); \
  EXTERN template void Eigen::PartialPivLU<Eigen::MatrixXd>::compute();                          \
  EXTERN template struct Eigen::internal::partial_lu_impl<double, 0, int, -1>;                   \
  EXTERN template struct Eigen::internal::gebp_kernel<                                           \
      double, double, Eigen::Index, Eigen::internal::blas_data_mapper<double, Eigen::Index, 0, 0, 1>, \
      4, 4, false, false>;                                                                       \
  EXTERN template struct Eigen::internal::general_matrix_vector_product<                         \
      Eigen::Index, double, Eigen::internal::const_blas_data_mapper<double, Eigen::Index, 1>, 1,  \
      false, double, Eigen::internal::const_blas_data_mapper<double, Eigen::Index, 0>, false, 0>; \
  EXTERN template struct Eigen::internal::general_matrix_vector_product<                         \
      Eigen::Index, double, Eigen::internal::const_blas_data_mapper<double, Eigen::Index, 0>, 0,  \
      false, double, Eigen::internal::const_blas_data_mapper<double, Eigen::Index, 1>, false, 0>; \
  EXTERN template struct Eigen::internal::general_matrix_matrix_product<                         \
      Eigen::Index, double, 0, false, double, 0, false, 0, 1>;                                   \
  EXTERN template struct Eigen::internal::triangular_solve_vector<double, double, Eigen::Index, 1, \
                                                                  5, false, 0>;                  \
  EXTERN template struct Eigen::internal::triangular_solve_vector<double, double, Eigen::Index, 1, \
                                                                  2, false, 0>;                  \
  EXTERN template struct Eigen::internal::triangular_solve_matrix<double, Eigen::Index, 1, 2,    \
                                                                  false, 0, 0, 1>;               \
  EXTERN template struct Eigen::internal::triangular_solve_matrix<double, Eigen::Index, 1, 5,    \
                                                                  false, 0, 0, 1>;

FFDKIT_EIGEN_DENSE_INSTANCES(extern)
