// The one definition of each Eigen instance that eigen_dense_instances.h and
// eigen_sparse_lu_instance.h declare.
#include <Eigen/Dense>
#include <Eigen/SparseLU>

#define FFDKIT_NOTHING
#include "eigen_dense_instances.h"
#include "eigen_sparse_lu_instance.h"

FFDKIT_EIGEN_DENSE_INSTANCES(FFDKIT_NOTHING)
FFDKIT_EIGEN_SPARSE_LU_INSTANCE(FFDKIT_NOTHING)
