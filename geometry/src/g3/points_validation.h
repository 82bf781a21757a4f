#pragma once
// Internal: shared validation of data points.

#include <Eigen/Core>

namespace ffdkit::geometry::g3::detail {

/// @throws G3InputError for < 2 rows, non-finite coordinates or coincident consecutive points.
void validatePoints(const Eigen::Ref<const Eigen::MatrixX2d>& points, const char* where);

}  // namespace ffdkit::geometry::g3::detail
