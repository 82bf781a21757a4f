#pragma once

// The bases the property panel offers for a lattice axis, and their names.

#include <vector>

#include <QString>

#include "ffdkit/ffd/axis_basis.h"

namespace ffdkit::app {

/// "Bernstein", "B-spline deg 2", "periodic B-spline deg 3", "B-spline deg 3, knots".
QString basisName(const ffd::AxisBasis& b);
/// The bases a lattice axis offers: Bernstein and clamped B-splines of degree 1-3, or, for the
/// angular axis of a cylindrical lattice, periodic B-splines of degree 1-3; plus the current
/// basis when it is none of these (explicit knots, a higher degree), so the combo can show it.
std::vector<ffd::AxisBasis> basisChoices(const ffd::AxisBasis& current, bool angular);
/// The index of `b` in `choices` (same kind, degree and knot count), or -1.
int basisIndex(const std::vector<ffd::AxisBasis>& choices, const ffd::AxisBasis& b);

}  // namespace ffdkit::app
