#include "ffdkit/interaction/cell_from_selection.h"

#include <algorithm>
#include <set>
#include <stdexcept>

namespace ffdkit::app {

using widgets::CellKind;
using widgets::CellSpec;

namespace {

Eigen::Vector3i grid(const Eigen::Vector3i& n, Eigen::Index flat) {
  const auto l = static_cast<Eigen::Index>(n.x()), m = static_cast<Eigen::Index>(n.y());
  return {static_cast<int>(flat % l), static_cast<int>((flat / l) % m), static_cast<int>(flat / (l * m))};
}

std::string str(const Eigen::Vector3i& g) {
  std::string s(1, '(');
  for (int a = 0; a < 3; ++a) {
    s += std::to_string(g[a]);
    s += a < 2 ? ',' : ')';
  }
  return s;
}

const char* axisName(int a) { return a == 0 ? "i" : a == 1 ? "j" : "k"; }

std::string points(std::size_t n) { return std::to_string(n) + (n == 1 ? " point is" : " points are") + " selected"; }

/// The selection's grid box: lower and upper corner.
std::pair<Eigen::Vector3i, Eigen::Vector3i> bounds(const std::vector<Eigen::Vector3i>& g) {
  Eigen::Vector3i lo = g.front(), hi = g.front();
  for (const auto& p : g) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo, hi};
}

/// True when `g` (distinct points) is every grid point of the box [lo, hi].
bool fillsBox(const std::vector<Eigen::Vector3i>& g, const Eigen::Vector3i& lo, const Eigen::Vector3i& hi) {
  return static_cast<long>(g.size()) == static_cast<long>((hi - lo + Eigen::Vector3i::Ones()).prod());
}

CellFromSelection fit(const Eigen::Vector3i& n, const std::vector<Eigen::Index>& indices, CellKind kind) {
  CellFromSelection out;
  const std::size_t count = indices.size();
  std::vector<Eigen::Vector3i> g;
  for (Eigen::Index i : indices) g.push_back(grid(n, i));
  switch (kind) {
    case CellKind::Point:
      if (count != 1) {
        out.why = "a point cell is 1 point; " + points(count);
        return out;
      }
      out.spec = CellSpec::point(g[0].x(), g[0].y(), g[0].z());
      return out;
    case CellKind::Edge: {
      if (count != 2) {
        out.why = "an edge cell is 2 neighbouring points; " + points(count);
        return out;
      }
      const Eigen::Vector3i d = (g[1] - g[0]).cwiseAbs();
      int axis = -1;
      for (int a = 0; a < 3; ++a)
        if (d[a] != 0) axis = (axis == -1 && d[a] == 1) ? a : 3;
      if (axis < 0 || axis > 2) {
        std::string differ;
        for (int a = 0; a < 3; ++a)
          if (d[a] != 0) differ += (differ.empty() ? "" : ", ") + std::to_string(d[a]) + " along " + axisName(a);
        out.why = "an edge cell is 2 neighbouring points along one axis; " + str(g[0]) + " and " + str(g[1]) +
                  " differ by " + differ;
        return out;
      }
      const Eigen::Vector3i lo = g[0].cwiseMin(g[1]);
      out.spec = CellSpec::edge(lo.x(), lo.y(), lo.z(), axis);
      return out;
    }
    case CellKind::Face: {
      if (count != 4) {
        out.why = "a face cell is the 4 corners of one grid quad; " + points(count);
        return out;
      }
      const auto [lo, hi] = bounds(g);
      const Eigen::Vector3i span = hi - lo;
      int flat = -1, steps = 0;
      for (int a = 0; a < 3; ++a) {
        if (span[a] == 0) flat = a;
        if (span[a] == 1) ++steps;
      }
      if (flat < 0 || steps != 2 || !fillsBox(g, lo, hi)) {
        out.why = "a face cell is the 4 corners of one grid quad (one step along two axes, one plane); the points span " +
                  str(lo) + " to " + str(hi);
        return out;
      }
      out.spec = CellSpec::face(lo.x(), lo.y(), lo.z(), flat);
      return out;
    }
    case CellKind::Box: {
      if (count != 8) {
        out.why = "a box cell is the 8 corners of one grid hexahedron; " + points(count);
        return out;
      }
      const auto [lo, hi] = bounds(g);
      if ((hi - lo) != Eigen::Vector3i::Ones() || !fillsBox(g, lo, hi)) {
        out.why = "a box cell is the 8 corners of one grid hexahedron (one step along each axis); the points span " +
                  str(lo) + " to " + str(hi);
        return out;
      }
      out.spec = CellSpec::box(lo.x(), lo.y(), lo.z());
      return out;
    }
    case CellKind::Slab: {
      const auto [lo, hi] = bounds(g);
      for (int a = 0; a < 3; ++a) {
        if (lo[a] != hi[a]) continue;
        const long plane = static_cast<long>(n.prod() / n[a]);
        if (static_cast<long>(count) == plane) {
          out.spec = CellSpec::slab(a, lo[a]);
          return out;
        }
        out.why = "a slab cell is every point of one index plane: plane " + std::string(axisName(a)) + " = " +
                  std::to_string(lo[a]) + " has " + std::to_string(plane) + " points and " + points(count);
        return out;
      }
      out.why = "a slab cell is every point of one index plane; the points span " + str(lo) + " to " + str(hi) +
                ", in no one plane";
      return out;
    }
    case CellKind::Custom:
      if (count == 0) {
        out.why = "a custom cell needs at least one point; none is selected";
        return out;
      }
      out.spec = CellSpec::custom(indices);
      return out;
  }
  return out;
}

}  // namespace

CellFromSelection cellFromSelection(const Eigen::Vector3i& counts, const std::vector<Eigen::Index>& indices,
                                    CellKind kind) {
  if ((counts.array() < 2).any()) throw std::invalid_argument("a lattice needs >= 2 points per axis");
  const Eigen::Index total = static_cast<Eigen::Index>(counts.prod());
  std::set<Eigen::Index> seen;
  for (Eigen::Index i : indices) {
    if (i < 0 || i >= total)
      throw std::invalid_argument("point " + std::to_string(i) + " outside [0, " + std::to_string(total - 1) + "]");
    if (!seen.insert(i).second) throw std::invalid_argument("point " + std::to_string(i) + " is listed twice");
  }
  if (indices.empty() && kind != CellKind::Custom) {
    CellFromSelection out;
    out.why = "no point is selected";
    return out;
  }
  return fit(counts, indices, kind);
}

std::optional<CellSpec> classifySelection(const Eigen::Vector3i& counts, const std::vector<Eigen::Index>& indices) {
  if (indices.empty()) return std::nullopt;
  for (CellKind kind : {CellKind::Point, CellKind::Edge, CellKind::Face, CellKind::Box, CellKind::Slab})
    if (auto fitted = cellFromSelection(counts, indices, kind); fitted.spec) return fitted.spec;
  return std::nullopt;
}

std::optional<std::string> affineRefusal(widgets::AffineKind kind, CellKind cellKind) {
  if (cellKind != CellKind::Point || kind == widgets::AffineKind::Translate) return std::nullopt;
  return std::string("a ") + (kind == widgets::AffineKind::Rotate ? "rotate" : "scale") +
         " widget on a point cell sits at the point and would " + (kind == widgets::AffineKind::Rotate ? "turn" : "size") +
         " it about itself, which moves nothing: select two or more points and Make Cell (an edge, face, slab, box "
         "or custom cell turns and sizes), or add a translate widget (a point cell carries translation, mask T)";
}

}  // namespace ffdkit::app
