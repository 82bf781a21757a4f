// Eigen's SparseLU on a column-major double matrix (the curve-network tangent systems, the
// cardinal shape-point systems), compiled once in eigen_instances.cpp (ffdkit::geometry_core):
// see eigen_dense_instances.h. Included by the sources that factor such a matrix.
#pragma once

#include <Eigen/SparseLU>

#define FFDKIT_EIGEN_SPARSE_LU_INSTANCE(EXTERN)                                                  \
  EXTERN template void Eigen::SparseLU<Eigen::SparseMatrix<double>>::analyzePattern(              \
      const Eigen::SparseMatrix<double>&);                                                       \
  EXTERN template void Eigen::SparseLU<Eigen::SparseMatrix<double>>::factorize(                  \
      const Eigen::SparseMatrix<double>&);                                                       \
  EXTERN template class Eigen::internal::SparseLUImpl<double, int>;

FFDKIT_EIGEN_SPARSE_LU_INSTANCE(extern)
