#pragma once

#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ffdkit/widgets/ray.h"

namespace ffdkit::app {

/// The handles of a transformer manipulator (Kuriyama 1996, sec. 6.2.1: the user sets an affine widget's
/// placement, or a lattice widget's frame, with a transformer). Move along an axis, turn about
/// an axis, size along an axis (a lattice) or uniformly (an affine widget: any size handle).
enum class TransformerHandle { MoveX, MoveY, MoveZ, TurnX, TurnY, TurnZ, SizeX, SizeY, SizeZ };

/// Axis 0, 1, 2 of a handle.
int transformerAxis(TransformerHandle handle);
/// "move x", "turn z", ...
const char* transformerHandleName(TransformerHandle handle);

/// Where a transformer is drawn and picked: a rigid world frame (the widget's origin and axes)
/// and a size in world units. All handle positions are multiples of `size`, in that frame
/// (TransformerLayout).
struct Transformer {
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
  double size = 1.0;
  bool uniformSize = false;  ///< every size handle scales all three axes alike (affine widgets)
  /// Equal when frame, size and uniformSize are (a transformer drawn the same).
  friend bool operator==(const Transformer& a, const Transformer& b) {
    return a.frame.matrix() == b.frame.matrix() && a.size == b.size && a.uniformSize == b.uniformSize;
  }
};

/// The shape of a transformer, in units of Transformer::size, in its frame. No two handles meet
/// in space. The inner part of each axis (below moveFrom) is left free so that the widget's own
/// glyph (an arrow of length 0.4, a ring of radius 0.4 when the transformer is 2.5 glyph sizes)
/// can still be grabbed.
struct TransformerLayout {
  static constexpr double moveFrom = 0.45;   ///< move shaft from here ...
  static constexpr double moveTo = 0.8;      ///< ... to here, then a cone to moveTip
  static constexpr double moveTip = 0.95;
  static constexpr double turnRadius = 1.05; ///< rings about each axis, clear of the shafts
  static constexpr double sizeAt = 1.3;      ///< centre of the size cube on each axis, outside the rings
  static constexpr double sizeHalf = 0.07;   ///< half width of the size cube
};

/// Nearest handle under `ray` within `tolerance` (world units; the cubes count as spheres of
/// radius sizeHalf * size + tolerance); nullopt on a miss.
std::optional<TransformerHandle> pickTransformer(const Transformer& transformer, const widgets::Ray& ray,
                                                 double tolerance);

/// One drag of one handle: the world motion since the press, computed from the press state
/// only (no drift; the rule for gestures, applied to the manipulator).
/// - Move: along the axis line, by the change of the closest point to the ray.
/// - Turn: about the axis through the origin, by the unwrapped angle of the ray's hit in the
///   plane normal to the axis (several turns accumulate).
/// - Size: by the ratio of the closest axis parameters (now / at the press), about the origin,
///   along the axis (or uniformly), never below minFactor.
/// Rays parallel to the drag line or plane keep the last motion.
class TransformerDrag {
 public:
  static constexpr double minFactor = 0.02;

  TransformerDrag(const Transformer& atPress, TransformerHandle handle, const widgets::Ray& pressRay);
  /// The world motion since the press for the current ray.
  Eigen::Affine3d motion(const widgets::Ray& ray);
  TransformerHandle handle() const { return handle_; }
  /// The last motion's scalar: distance (world units), angle (rad) or factor.
  double value() const { return value_; }
  /// The world motion of this handle for a value (distance, rad or factor): a typed or snapped
  /// value instead of the pointer's.
  Eigen::Affine3d motionFor(double value) const;

 private:
  std::optional<double> axisParameter(const widgets::Ray& ray) const;
  std::optional<double> planeAngle(const widgets::Ray& ray) const;

  Transformer start_;
  TransformerHandle handle_;
  Eigen::Vector3d axis_;
  double startParameter_ = 0.0;  ///< move / size: the axis parameter at the press
  double lastAngle_ = 0.0;       ///< turn: the last raw angle, for unwrapping
  double value_;
};

}  // namespace ffdkit::app
