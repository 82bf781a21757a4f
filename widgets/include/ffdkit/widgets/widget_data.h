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
  std::string shape;
  double size = 0.2;
  Eigen::Affine3d partPlacement = Eigen::Affine3d::Identity();  ///< of a library part in the widget frame
  bool operator==(const Glyph& o) const {
    return shape == o.shape && size == o.size && partPlacement.matrix() == o.partPlacement.matrix();
  }
};

/// Plain data of a whole widget model: what a widget file holds (Kuriyama 1996, sec. 6.3.3). Lists
/// are in id order. WidgetModel::toData / WidgetModel::fromData convert; fromData validates
/// everything.
struct LatticeData {
  WidgetId id;
  std::string name;
  Eigen::Vector3i counts = Eigen::Vector3i::Constant(2);
  Eigen::MatrixX3d restPoints;     ///< pointCount x 3, lattice-local
  Eigen::MatrixX3d controlPoints;  ///< pointCount x 3, lattice-local
  /// Root lattice: its world frame (world = frame * local). Child lattice: its placement
  /// relative to the parent cell's masked current frame (see WidgetModel::latticeFrame).
  Eigen::Affine3d frame = Eigen::Affine3d::Identity();
  LatticeSettings settings;
  std::vector<WidgetId> children;  ///< child lattices in sibling order
};

struct CellData {
  WidgetId id;
  std::string name;
  WidgetId lattice;
  CellSpec spec;
};

struct AffineData {
  WidgetId id;
  std::string name;
  AffineKind kind = AffineKind::Translate;
  /// Relative to the cell's rest frame, or the world frame for a free widget (no attachment).
  Eigen::Affine3d placement = Eigen::Affine3d::Identity();
  double variation = 0.0;  ///< accumulated: distance, angle (rad) or log scale factor
  Glyph glyph;
};

struct WidgetModelData {
  std::vector<LatticeData> lattices;
  std::vector<CellData> cells;
  std::vector<AffineData> affines;
  std::vector<Binding> bindings;
  std::vector<WidgetId> rootOrder;  ///< root lattices in sibling order
};

}  // namespace ffdkit::widgets
