#pragma once

#include <Eigen/Core>

namespace ffdkit::geometry::polyhedron {

/// Minimum-norm solution G = A^+ R of the cyclic ring system G_i + G_{i-1} = R_i (indices
/// mod N, one row per ring edge / patch; Kuriyama 1996, secs. 4.3.1, 4.3.2, eq. (4.17)). For odd N
/// the system is regular and solved exactly; for even N it is singular (kernel (-1)^i) and this is
/// the thesis projection R~_i = R_i + (-1)^{i-1} Dif(R) / N with sum_i (-1)^i G_i = 0
/// (sec. 4.3.2), in the closed forms of Kuriyama 1996, sec. 4.3.2. Translation invariant.
/// @param r  N x 3, N >= 1
/// @throws std::invalid_argument if r has no rows.
Eigen::MatrixX3d ringTargets(const Eigen::MatrixX3d& r);

}  // namespace ffdkit::geometry::polyhedron
