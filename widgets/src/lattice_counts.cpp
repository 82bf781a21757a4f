#include "widget_model_impl.h"

#include "ffdkit/ffd/cylindrical_lattice.h"
#include "ffdkit/ffd/embedding.h"

namespace ffdkit::widgets {

// ---- setLatticeCounts ---------------------------------------------------------------------------
namespace {

// Index i of n grid points along an axis, moved to a grid of n2 points: the point at the same
// relative position (round(i (n2-1) / (n-1)); a periodic axis has no end point: round(i n2 / n) mod n2).
int remapGridIndex(int i, int n, int n2, bool periodic) {
  if (periodic) return static_cast<int>(std::lround(static_cast<double>(i) * n2 / n)) % n2;
  return static_cast<int>(std::lround(static_cast<double>(i) * (n2 - 1) / (n - 1)));
}

Eigen::Vector3i remapGrid(const Eigen::Vector3i& g, const Eigen::Vector3i& from, const Eigen::Vector3i& to,
                          const std::array<bool, 3>& periodic) {
  Eigen::Vector3i out;
  for (int a = 0; a < 3; ++a) out[a] = remapGridIndex(g[a], from[a], to[a], periodic[static_cast<std::size_t>(a)]);
  return out;
}

std::string countsString(const Eigen::Vector3i& c) {
  return std::string("(") + std::to_string(c.x()) + ", " + std::to_string(c.y()) + ", " + std::to_string(c.z()) + ")";
}

// The cell spec on the new grid (see setLatticeCounts); throws a message (without the cell's
// name) when the cell does not fit or collapses.
CellSpec remapCellSpec(const CellSpec& spec, const Eigen::Vector3i& from, const Eigen::Vector3i& to,
                       const std::array<bool, 3>& periodic) {
  CellSpec out = spec;
  switch (spec.kind) {
    case CellKind::Point:
    case CellKind::Edge:
    case CellKind::Face:
    case CellKind::Box: out.base = remapGrid(spec.base, from, to, periodic); break;
    case CellKind::Slab: {
      const auto a = static_cast<std::size_t>(spec.axis);
      if (spec.axis >= 0 && spec.axis < 3)
        out.base[spec.axis] = remapGridIndex(spec.base[spec.axis], from[spec.axis], to[spec.axis], periodic[a]);
      break;
    }
    case CellKind::Custom: {
      out.indices.clear();
      const Eigen::Index l = from.x(), m = from.y();
      for (Eigen::Index f : spec.indices) {
        const Eigen::Vector3i g(static_cast<int>(f % l), static_cast<int>((f / l) % m), static_cast<int>(f / (l * m)));
        const Eigen::Vector3i r = remapGrid(g, from, to, periodic);
        const Eigen::Index flat = r.x() + static_cast<Eigen::Index>(to.x()) * (r.y() + static_cast<Eigen::Index>(to.y()) * r.z());
        if (std::find(out.indices.begin(), out.indices.end(), flat) == out.indices.end()) out.indices.push_back(flat);
      }
      break;
    }
  }
  return out;
}

// n x n collocation matrix of an axis: row r holds the basis functions at params[r].
Eigen::MatrixXd collocation(const ffd::AxisSpline& axis, const Eigen::VectorXd& params) {
  const int n = axis.count();
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(params.size(), n);
  std::vector<double> values(static_cast<std::size_t>(axis.degree() + 1));
  for (Eigen::Index r = 0; r < params.size(); ++r) {
    const int cell = axis.cellOf(params[r]);
    axis.basis(cell, params[r], values.data());
    for (int q = 0; q <= axis.degree(); ++q) c(r, axis.controlIndex(cell, q)) += values[static_cast<std::size_t>(q)];
  }
  return c;
}

// Solves (N_w (x) N_v (x) N_u) X = B for X, B one row per grid point (i fastest), one axis at a time.
Eigen::MatrixX3d solveTensor(const std::array<Eigen::MatrixXd, 3>& n, const Eigen::Vector3i& counts, Eigen::MatrixX3d b) {
  const std::array<Eigen::Index, 3> stride{1, counts.x(), static_cast<Eigen::Index>(counts.x()) * counts.y()};
  for (std::size_t a = 0; a < 3; ++a) {
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(n[a]);
    const int len = counts[static_cast<int>(a)];
    Eigen::MatrixX3d line(len, 3);
    for (Eigen::Index start = 0; start < b.rows(); ++start) {
      if ((start / stride[a]) % len != 0) continue;  // first point of a line along axis a
      for (int r = 0; r < len; ++r) line.row(r) = b.row(start + r * stride[a]);
      const Eigen::MatrixX3d x = lu.solve(line);
      for (int r = 0; r < len; ++r) b.row(start + r * stride[a]) = x.row(r);
    }
  }
  return b;
}

}  // namespace

void WidgetModel::setLatticeCounts(WidgetId lattice, const Eigen::Vector3i& counts) {
  Impl& m = *impl_;
  m.requireNoGesture("changing a lattice's counts");
  const Impl::Node& n = m.node(lattice, WidgetType::Lattice);
  const std::string who = "lattice '" + m.label(lattice);
  if ((counts.array() < 2).any())
    fail(WidgetErrorCode::InvalidArgument, who + " needs >= 2 points per axis, got " + countsString(counts));
  if (static_cast<double>(counts.x()) * counts.y() * counts.z() > 1e8)
    fail(WidgetErrorCode::InvalidArgument, who + " would have too many control points (at most 1e8): " + countsString(counts));
  if (n.counts == counts) return;

  // The bases resolved for the new counts (a degree the count cannot carry fails here).
  std::array<ffd::AxisSpline, 3> axes;
  std::array<bool, 3> periodic{};
  for (int a = 0; a < 3; ++a) {
    const auto s = static_cast<std::size_t>(a);
    try {
      axes[s] = ffd::AxisSpline(n.settings.basis[s], counts[a], a == 0 ? "u" : a == 1 ? "v" : "w");
    } catch (const std::exception& e) {
      fail(WidgetErrorCode::InvalidArgument, who + " cannot take " + std::to_string(counts[a]) + " points along " + "uvw"[a] +
                                                 " with its basis: " + e.what());
    }
    periodic[s] = axes[s].periodic();
  }

  // Cells on the new grid, all checked before anything changes.
  const std::vector<WidgetId> cellIds = n.cells;
  std::vector<CellSpec> specs;
  std::vector<std::vector<Eigen::Index>> indices;
  for (WidgetId c : cellIds) {
    const CellSpec& old = m.nodes[c.value].spec;
    const std::string cellWho = "cell '" + m.label(c) + " (" + std::string(cellKindName(old.kind)) + ")";
    CellSpec spec = remapCellSpec(old, n.counts, counts, periodic);
    try {
      indices.push_back(cellPointIndices(counts, spec));
    } catch (const WidgetError& e) {
      fail(WidgetErrorCode::InvalidArgument, "cannot change " + who + " to " + countsString(counts) + ": " + cellWho +
                                                 " does not fit on the new grid (" + e.message() + ")");
    }
    specs.push_back(std::move(spec));
  }

  // Parameters of the new grid: the Greville abscissae of the new bases, and the same relative
  // position in the old parameter box.
  const ffd::Lattice old = Impl::makeFfd(n.counts, n.settings, n.rest, n.control, Eigen::Affine3d::Identity(), n.weights);
  const Eigen::Index total = static_cast<Eigen::Index>(counts.prod());
  Eigen::MatrixX3d params(total, 3), oldParams(total, 3);
  for (Eigen::Index f = 0; f < total; ++f) {
    const Eigen::Vector3i g(static_cast<int>(f % counts.x()), static_cast<int>((f / counts.x()) % counts.y()),
                            static_cast<int>(f / (static_cast<Eigen::Index>(counts.x()) * counts.y())));
    for (int a = 0; a < 3; ++a) {
      const ffd::AxisSpline& ax = axes[static_cast<std::size_t>(a)];
      const double t = ax.greville()[g[a]];
      params(f, a) = t;
      const ffd::AxisSpline& o = old.axis(a);
      oldParams(f, a) = o.domainMin() + (t - ax.domainMin()) * (o.domainMax() - o.domainMin()) / (ax.domainMax() - ax.domainMin());
    }
  }

  // New rest points: a box stays the same box (its affine rest map at the new parameters), a
  // cylinder the same analytic cylinder, a user-shaped lattice samples its old rest map.
  Eigen::MatrixX3d rest(total, 3);
  const bool cylinder = n.settings.cylinder.has_value() && periodic[1];
  if (cylinder) {
    ffd::CylindricalLatticeOptions o;
    o.counts = counts;
    o.bases = n.settings.basis;
    o.innerRadius = n.settings.cylinder->innerRadius;
    o.outerRadius = n.settings.cylinder->outerRadius;
    o.zMin = n.settings.cylinder->zMin;
    o.zMax = n.settings.cylinder->zMax;
    try {
      rest = ffd::makeCylindricalLattice(o).restPoints();
    } catch (const std::exception& e) {
      fail(WidgetErrorCode::InvalidArgument, who + ": " + e.what());
    }
  } else {
    for (Eigen::Index f = 0; f < total; ++f) {
      const Eigen::Vector3d t = oldParams.row(f).transpose();
      rest.row(f) = (old.restIsAffine() ? Eigen::Vector3d(old.restAffineLinear() * t + old.restAffineOffset())
                                        : old.evaluateRest(t))
                        .transpose();
    }
  }
  const ffd::Lattice fresh = Impl::makeFfd(counts, n.settings, rest, rest, Eigen::Affine3d::Identity());

  // The deformation to keep, as a displacement d(x) = X(p) - Xbar(p) of rest-space points x =
  // Xbar(p), sampled where the new lattice's rest map puts its grid parameters; the new control
  // displacements interpolate these samples (tensor-product collocation at the Greville
  // abscissae). Exactly zero for an undeformed lattice; exact for an affine deformation (every
  // basis reproduces affine maps) and when the old displacement lies in the new lattice's space
  // (a Bernstein axis raised from n to n' > n points: degree elevation). An axis that loses
  // points samples the old displacement instead of interpolating it: detail the coarser lattice
  // cannot hold would make the interpolant overshoot (a random 30-point cubic B-spline
  // displacement interpolated by 5 points: control displacements 2.4x the old ones).
  Eigen::MatrixX3d at = oldParams;  // parameters of the samples in the old lattice
  if (!old.restIsAffine() || cylinder) {
    Eigen::MatrixX3d samples(total, 3);
    for (Eigen::Index f = 0; f < total; ++f) samples.row(f) = fresh.evaluateRest(params.row(f).transpose()).transpose();
    ffd::EmbedOptions eo;
    eo.parallel = false;
    const ffd::Embedding e = ffd::embed(old, samples, eo);
    if (e.failedCount() > 0)
      fail(WidgetErrorCode::InvalidArgument, "cannot change " + who + " to " + countsString(counts) + ": " +
                                                 std::to_string(e.failedCount()) + " new grid points could not be located in the old lattice");
    at = e.parameters();
  }
  Eigen::MatrixX3d displacement(total, 3);
  for (Eigen::Index f = 0; f < total; ++f) {
    const Eigen::Vector3d p = at.row(f).transpose();
    displacement.row(f) = (old.evaluate(p) - old.evaluateRest(p)).transpose();
  }
  if (!displacement.isZero(0.0)) {
    std::array<Eigen::MatrixXd, 3> colloc;
    for (int a = 0; a < 3; ++a) {
      const auto s = static_cast<std::size_t>(a);
      const bool sample = counts[a] < n.counts[a];
      colloc[s] = sample ? Eigen::MatrixXd::Identity(counts[a], counts[a]) : collocation(axes[s], axes[s].greville());
    }
    displacement = solveTensor(colloc, counts, displacement);
  }
  const Eigen::MatrixX3d control = rest + displacement;
  if (!finite(control))
    fail(WidgetErrorCode::InvalidArgument, "cannot change " + who + " to " + countsString(counts) + ": the resampled points are not finite");

  // Child lattices keep their world frame (the deformation they add stays where it was).
  std::vector<std::pair<WidgetId, Eigen::Affine3d>> childWorld;
  for (WidgetId child : n.children) childWorld.emplace_back(child, m.latticeFrame(m.nodes[child.value]));

  // Commit: nothing below throws.
  Impl::Node& w = m.nodes[lattice.value];
  w.counts = counts;
  w.rest = rest;
  w.control = control;
  w.weights.resize(0);  // the resampled points carry the old (rational) shape; the new weights are 1
  for (std::size_t c = 0; c < cellIds.size(); ++c) {
    Impl::Node& cell = m.nodes[cellIds[c].value];
    cell.spec = std::move(specs[c]);
    cell.indices = std::move(indices[c]);
    cell.restCellPoints = detail::gatherRows(rest, cell.indices);
    cell.restFrame = widgets::cellRestFrame(cell.spec, counts, cell.restCellPoints);
  }
  for (const auto& [child, world] : childWorld) {
    Impl::Node& ch = m.nodes[child.value];
    const Binding& b = *m.bindings[ch.parentBinding.value];
    const Impl::Node& cell = m.nodes[b.from.value];
    ch.frame = (m.latticeFrame(w) * m.maskedCellFrame(cell, b.mask)).inverse() * world;
  }
  m.touch();
  m.markStructure();  // its cells hold other points
  m.markWidget(lattice);
  m.markControl(lattice);
  m.markRest(lattice);
  for (WidgetId cell : m.nodes[lattice.value].cells) m.markWidget(cell);
}

}  // namespace ffdkit::widgets
