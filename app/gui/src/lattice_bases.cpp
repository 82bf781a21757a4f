#include "lattice_bases.h"

#include <algorithm>

namespace ffdkit::app {

QString basisName(const ffd::AxisBasis& b) {
  switch (b.kind) {
    case ffd::AxisBasis::Kind::Bernstein: return "Bernstein";
    case ffd::AxisBasis::Kind::BSpline:
      return QString(b.knots.size() > 0 ? "B-spline deg %1, knots" : "B-spline deg %1").arg(b.degree);
    case ffd::AxisBasis::Kind::PeriodicBSpline: return QString("periodic B-spline deg %1").arg(b.degree);
  }
  return "?";
}

std::vector<ffd::AxisBasis> basisChoices(const ffd::AxisBasis& current, bool angular) {
  std::vector<ffd::AxisBasis> out;
  if (angular) {
    for (int d = 1; d <= 3; ++d) out.push_back(ffd::AxisBasis::periodic(d));
  } else {
    out.push_back(ffd::AxisBasis::bernstein());
    for (int d = 1; d <= 3; ++d) out.push_back(ffd::AxisBasis::bspline(d));
  }
  const bool listed = std::any_of(out.begin(), out.end(), [&](const ffd::AxisBasis& b) {
    return b.kind == current.kind && (b.kind == ffd::AxisBasis::Kind::Bernstein || b.degree == current.degree) &&
           current.knots.size() == 0;
  });
  if (!listed) out.push_back(current);
  return out;
}

int basisIndex(const std::vector<ffd::AxisBasis>& choices, const ffd::AxisBasis& b) {
  for (std::size_t i = 0; i < choices.size(); ++i) {
    const ffd::AxisBasis& c = choices[i];
    if (c.kind == b.kind && (c.kind == ffd::AxisBasis::Kind::Bernstein || c.degree == b.degree) &&
        c.knots.size() == b.knots.size())
      return static_cast<int>(i);
  }
  return -1;
}

}  // namespace ffdkit::app
