#pragma once

#include <vector>

#include "ffdkit/geometry/cardinal/sigma_curve.h"
#include "ffdkit/geometry/cardinal/sigma_knots.h"
#include "ffdkit/geometry/cardinal/sigma_surface.h"

namespace ffdkit::geometry::cardinal {

/// The knot vector after inserting `newKnots` (strictly inside (t_0, t_n); values within
/// 1e-9 * range of an existing or earlier knot are ignored). Inserted knots get beta2 = 0;
/// open ends keep their phantom widths rule (unset phantoms: widths of the new end intervals).
/// @throws CardinalSplineError if a new knot lies outside (t_0, t_n).
SigmaKnots refinedKnots(const SigmaKnots& knots, const std::vector<double>& newKnots);

/// Knot insertion for a sigma-spline curve: the geometry is unchanged. Each quartic piece is
/// split by de Casteljau; Ptilde_i = b0, Phattilde_i = b2 of the new pieces; open-end shape
/// points solve b1 of the first and b3 of the last piece (Kuriyama 1996, secs. 3.3.6, 3.2.2 item
/// 14).
/// @see Kuriyama 1996, sec. 3.3.6.
SigmaCurve refine(const SigmaCurve& curve, const std::vector<double>& newKnots);

/// Knot insertion for a sigma-spline surface in u and v (row by row, then column by column).
SigmaSurface refine(const SigmaSurface& surface, const std::vector<double>& newU,
                    const std::vector<double>& newV);

}  // namespace ffdkit::geometry::cardinal
