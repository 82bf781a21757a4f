#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ffdkit/widgets/affine_kind.h"
#include "ffdkit/widgets/binding.h"
#include "ffdkit/widgets/cell.h"
#include "ffdkit/widgets/lattice_settings.h"
#include "ffdkit/widgets/widget_id.h"

namespace ffdkit::widgets {

/// Glyph of an affine widget (Kuriyama 1996, sec. 6.4): the default shape per kind is "arrow"
/// (translate), "ring" (rotate), "cube" (scale); any other name refers to a part of a parts library
/// (crank handle, lever, screw...) that the renderer resolves. `size` is in widget units.
struct Glyph {
  std::string shape;  ///< "arrow", "ring", "cube" or a part of a parts library
  double size = 0.2;  ///< in widget units
  Eigen::Affine3d partPlacement = Eigen::Affine3d::Identity();  ///< of a library part in the widget frame
  /// Equal when shape, size and part placement are.
  bool operator==(const Glyph& o) const {
    return shape == o.shape && size == o.size && partPlacement.matrix() == o.partPlacement.matrix();
  }
};

/// Plain data of a whole widget model: what a widget file holds (Kuriyama 1996, sec. 6.3.3). Lists
/// are in id order. WidgetModel::toData / WidgetModel::fromData convert; fromData validates
/// everything.
struct LatticeData {
  WidgetId id;  ///< the lattice widget's id
  std::string name;  ///< unique name
  Eigen::Vector3i counts = Eigen::Vector3i::Constant(2);  ///< control points per axis (l, m, n)
  Eigen::MatrixX3d restPoints;     ///< pointCount x 3, lattice-local
  Eigen::MatrixX3d controlPoints;  ///< pointCount x 3, lattice-local
  /// Root lattice: its world frame (world = frame * local). Child lattice: its placement
  /// relative to the parent cell's masked current frame (see WidgetModel::latticeFrame).
  Eigen::Affine3d frame = Eigen::Affine3d::Identity();
  LatticeSettings settings;  ///< bases, outside policy, re-embedding
  std::vector<WidgetId> children;  ///< child lattices in sibling order
  /// A weight > 0 per control point (rational lattice, Lamousin & Waggenspack 1994), same order
  /// as the points; empty when every weight is 1 (the rest lattice's weights are always 1).
  Eigen::VectorXd weights;
};

/// A cell widget: a group of a lattice's points.
struct CellData {
  WidgetId id;  ///< the cell's id
  std::string name;  ///< unique name
  WidgetId lattice;  ///< the lattice it belongs to
  CellSpec spec;  ///< which points it groups
};

/// An affine widget: translate, rotate or scale, on a cell or free.
struct AffineData {
  WidgetId id;  ///< the widget's id
  std::string name;  ///< unique name
  AffineKind kind = AffineKind::Translate;  ///< translate, rotate or scale
  /// Relative to the cell's rest frame, or the world frame for a free widget (no attachment).
  Eigen::Affine3d placement = Eigen::Affine3d::Identity();
  double variation = 0.0;  ///< accumulated: distance, angle (rad) or log scale factor
  Glyph glyph;  ///< how it is drawn and picked
};

/// A whole widget model as plain data (what a widget file holds).
struct WidgetModelData {
  std::vector<LatticeData> lattices;  ///< in id order
  std::vector<CellData> cells;  ///< in id order
  std::vector<AffineData> affines;  ///< in id order
  std::vector<Binding> bindings;  ///< in id order
  std::vector<WidgetId> rootOrder;  ///< root lattices in sibling order
};

}  // namespace ffdkit::widgets
