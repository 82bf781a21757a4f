#pragma once
// Internal: points between OpenCASCADE and Eigen.

#include <Eigen/Core>
#include <gp_Pnt.hxx>

namespace ffdkit::cad::detail {

inline Eigen::Vector3d toEigen(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }
inline gp_Pnt toPnt(const Eigen::Vector3d& p) { return gp_Pnt(p.x(), p.y(), p.z()); }

}  // namespace ffdkit::cad::detail
