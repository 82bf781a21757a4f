#include "widget_model_impl.h"

#include "ffdkit/widgets/glyph_shape.h"

namespace ffdkit::widgets {

// ---- rays ---------------------------------------------------------------------------------------
std::optional<PickResult> WidgetModel::pick(const Ray& ray, const PickOptions& options) const {
  const Impl& m = *impl_;
  const double tol = options.tolerance;
  const Eigen::Vector3d dir = ray.direction.normalized();
  std::optional<PickResult> best;
  int bestRank = 0;
  auto offer = [&](WidgetId id, double t, int rank) {
    // Nearest wins; within the tolerance an affine glyph beats a cell, a cell beats a lattice.
    if (!best || t < best->t - tol || (t <= best->t + tol && rank < bestRank) || (t < best->t && rank == bestRank)) {
      best = PickResult{id, t, ray.origin + t * dir};
      bestRank = rank;
    }
  };
  auto quad = [&](WidgetId id, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& d, int rank) {
    if (auto t = intersectTriangle(ray, a, b, c)) offer(id, *t, rank);
    if (auto t = intersectTriangle(ray, a, c, d)) offer(id, *t, rank);
  };
  auto sphere = [&](WidgetId id, const Eigen::Vector3d& p, double radius, int rank) {
    auto h = closestRaySegment(ray, p, p);
    if (h && h->distance <= radius) offer(id, h->t, rank);
  };
  for (const auto& n : m.nodes) {
    if (!n.alive) continue;
    if (n.type == WidgetType::Affine && options.affines) {
      const WidgetFrame f = affineFrame(n.id);
      const Eigen::Vector3d o = f.frame.translation();
      const Eigen::Matrix3d r = f.frame.linear();
      switch (n.kind) {
        case AffineKind::Translate: {
          auto h = closestRaySegment(ray, o, o + GlyphShape::arrowLength * f.size * r.col(0));
          if (h && h->distance <= tol + GlyphShape::pickThickness * f.size) offer(n.id, h->t, 0);
          break;
        }
        case AffineKind::Rotate: {
          if (auto t = intersectPlane(ray, o, r.col(2))) {
            const double rad = (ray.origin + *t * dir - o).norm();
            if (std::abs(rad - GlyphShape::ringRadius * f.size) <= tol + GlyphShape::pickThickness * f.size)
              offer(n.id, *t, 0);
          }
          break;
        }
        case AffineKind::Scale: {
          const double half = GlyphShape::cubeHalfWidth * f.size + tol;
          const Eigen::Vector3d lo = r.transpose() * (ray.origin - o);
          const Eigen::Vector3d ld = r.transpose() * dir;
          double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
          bool hit = true;
          for (int a = 0; a < 3 && hit; ++a) {
            if (std::abs(ld[a]) < 1e-15) {
              hit = std::abs(lo[a]) <= half;
            } else {
              double ta = (-half - lo[a]) / ld[a], tb = (half - lo[a]) / ld[a];
              if (ta > tb) std::swap(ta, tb);
              t0 = std::max(t0, ta);
              t1 = std::min(t1, tb);
              hit = t0 <= t1;
            }
          }
          if (hit) offer(n.id, t0, 0);
          break;
        }
      }
    } else if (n.type == WidgetType::Cell && options.cells) {
      const Eigen::MatrixX3d p = cellWorldPoints(n.id);
      auto row = [&](Eigen::Index i) -> Eigen::Vector3d { return p.row(i).transpose(); };
      switch (n.spec.kind) {
        case CellKind::Edge: {
          auto h = closestRaySegment(ray, row(0), row(1));
          if (h && h->distance <= tol) offer(n.id, h->t, 1);
          break;
        }
        case CellKind::Face: quad(n.id, row(0), row(1), row(2), row(3), 1); break;
        case CellKind::Slab: {
          const Eigen::Vector3i& c = m.nodes[n.lattice.value].counts;
          const int na = c[(n.spec.axis + 1) % 3], nc = c[(n.spec.axis + 2) % 3];
          for (int ic = 0; ic + 1 < nc; ++ic)
            for (int ia = 0; ia + 1 < na; ++ia)
              quad(n.id, row(ic * na + ia), row(ic * na + ia + 1), row((ic + 1) * na + ia + 1), row((ic + 1) * na + ia), 1);
          break;
        }
        case CellKind::Box: {
          static constexpr int faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
          for (const auto& f : faces) quad(n.id, row(f[0]), row(f[1]), row(f[2]), row(f[3]), 1);
          break;
        }
        case CellKind::Point:
        case CellKind::Custom:
          for (Eigen::Index i = 0; i < p.rows(); ++i) sphere(n.id, row(i), tol, 1);
          break;
      }
    } else if (n.type == WidgetType::Lattice && options.lattices) {
      const Eigen::MatrixX3d p = worldControlPoints(n.id);
      const Eigen::Vector3d lo = p.colwise().minCoeff().transpose().array() - tol;
      const Eigen::Vector3d hi = p.colwise().maxCoeff().transpose().array() + tol;
      double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
      bool hit = true;
      for (int a = 0; a < 3 && hit; ++a) {
        if (std::abs(dir[a]) < 1e-15) {
          hit = ray.origin[a] >= lo[a] && ray.origin[a] <= hi[a];
        } else {
          double ta = (lo[a] - ray.origin[a]) / dir[a], tb = (hi[a] - ray.origin[a]) / dir[a];
          if (ta > tb) std::swap(ta, tb);
          t0 = std::max(t0, ta);
          t1 = std::min(t1, tb);
          hit = t0 <= t1;
        }
      }
      if (hit) offer(n.id, t0, 2);
    }
  }
  return best;
}

void WidgetModel::beginDrag(WidgetId id, const Ray& ray) {
  Impl& m = *impl_;
  const Impl::Node& n = m.node(id);
  if (m.gesture) fail(WidgetErrorCode::GestureState, "a gesture on '" + m.label(m.gesture->target) + " is already active");
  Impl::Drag d;
  const Eigen::Vector3d dir = ray.direction.normalized();
  auto planePoint = [&](const Eigen::Vector3d& o, const Eigen::Vector3d& normal) -> Eigen::Vector3d {
    if (auto t = intersectPlane(ray, o, normal)) return ray.origin + *t * dir;
    // Edge-on: the ray point closest to o, projected into the plane.
    const Eigen::Vector3d p = ray.origin + std::max(0.0, (o - ray.origin).dot(dir)) * dir;
    return p - (p - o).dot(normal) * normal;
  };
  if (n.type == WidgetType::Affine) {
    const WidgetFrame f = affineFrame(id);
    d.frame = f.frame;
    d.origin = f.frame.translation();
    switch (n.kind) {
      case AffineKind::Translate: {
        d.mode = Impl::DragMode::Axis;
        d.axis = f.frame.linear().col(0);
        auto s = closestLineParameter(ray, d.origin, d.axis);
        if (!s) fail(WidgetErrorCode::InvalidArgument, "the ray runs along the translate axis: no drag direction");
        d.s0 = *s;
        break;
      }
      case AffineKind::Rotate: {
        d.mode = Impl::DragMode::Ring;
        d.axis = f.frame.linear().col(2);
        const Eigen::Vector3d v = f.frame.linear().transpose() * (planePoint(d.origin, d.axis) - d.origin);
        d.lastAngle = std::atan2(v.y(), v.x());
        break;
      }
      case AffineKind::Scale: {
        d.mode = Impl::DragMode::Radial;
        d.axis = dir;
        d.grab = planePoint(d.origin, d.axis);
        d.s0 = (d.grab - d.origin).norm();
        if (d.s0 <= 1e-12) fail(WidgetErrorCode::InvalidArgument, "grab the scale glyph off its centre");
        break;
      }
    }
  } else {
    d.mode = Impl::DragMode::Plane;
    d.axis = dir;
    const Eigen::Vector3d anchor = n.type == WidgetType::Cell ? cellFrame(id).frame.translation()
                                                              : Eigen::Vector3d(latticeFrame(id) * Eigen::Vector3d(0.5, 0.5, 0.5));
    auto t = intersectPlane(ray, anchor, dir);
    d.grab = ray.origin + (t ? *t : 0.0) * dir;
    d.origin = d.grab;
  }
  m.begin(id);
  m.gesture->drag = d;
}

void WidgetModel::dragTo(const Ray& ray) {
  Impl& m = *impl_;
  if (!m.gesture || !m.gesture->drag) fail(WidgetErrorCode::GestureState, "dragTo without beginDrag");
  Impl::Drag& d = *m.gesture->drag;
  const Eigen::Vector3d dir = ray.direction.normalized();
  switch (d.mode) {
    case Impl::DragMode::Axis: {
      if (auto s = closestLineParameter(ray, d.origin, d.axis)) d.lastDelta = *s - d.s0;
      updateGesture(d.lastDelta);
      break;
    }
    case Impl::DragMode::Ring: {
      if (auto t = intersectPlane(ray, d.origin, d.axis)) {
        const Eigen::Vector3d v = d.frame.linear().transpose() * (ray.origin + *t * dir - d.origin);
        if (v.head<2>().norm() > 1e-12) {
          const double a = std::atan2(v.y(), v.x());
          d.accumulated += wrapAngle(a - d.lastAngle);  // unwrap: several turns accumulate
          d.lastAngle = a;
        }
      }
      updateGesture(d.accumulated);
      break;
    }
    case Impl::DragMode::Radial: {
      if (auto t = intersectPlane(ray, d.origin, d.axis)) {
        const double r = (ray.origin + *t * dir - d.origin).norm();
        if (r > 1e-12) d.lastDelta = std::log(r / d.s0);
      }
      updateGesture(d.lastDelta);
      break;
    }
    case Impl::DragMode::Plane: {
      if (auto t = intersectPlane(ray, d.grab, d.axis)) {
        d.lastMotion = Eigen::Affine3d::Identity();
        d.lastMotion.translation() = ray.origin + *t * dir - d.grab;
      }
      updateGesture(d.lastMotion);
      break;
    }
  }
}

}  // namespace ffdkit::widgets
