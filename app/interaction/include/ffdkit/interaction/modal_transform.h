#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ffdkit/widgets/ray.h"

namespace ffdkit::app {

/// What G, R and S do to a selection (Blender's grab / rotate / scale).
enum class TransformMode { Move, Rotate, Scale };

/// About which point a selection turns and sizes: the mean of the selected items (median, as
/// Blender names it), the active (last picked) item, or each item about its own centre.
enum class PivotChoice { Median, Active, Individual };

/// An axis constraint typed during a transform: X, Y or Z keeps to that world axis; Shift+axis
/// excludes it (the plane of the other two). axis < 0: free (the view plane).
struct AxisConstraint {
  int axis = -1;
  bool exclude = false;
  bool free() const { return axis < 0; }
  /// The constraint after pressing an axis key (Blender): the same key again frees it.
  AxisConstraint pressed(int key, bool shift) const;
  /// "", "along x", "in the yz plane".
  std::string describe() const;
  friend bool operator==(const AxisConstraint&, const AxisConstraint&) = default;
};

/// A number typed during a transform ("0.5", "-90", "0.1,0,0.25"): digits, '.', '-' and ','
/// (components of a move); Backspace removes the last character.
class TypedValue {
 public:
  /// Adds a character; @return false (and nothing changes) for any other character.
  bool type(char c);
  void backspace();
  void clear() { text_.clear(); }
  bool empty() const { return text_.empty(); }
  const std::string& text() const { return text_; }
  /// The components typed so far (1 to 3 numbers); nullopt while the text is not a number yet
  /// ("-", "", "1,").
  std::optional<Eigen::Vector3d> components(int* count = nullptr) const;

 private:
  std::string text_;
};

/// Increments of Ctrl-snapping.
struct SnapSteps {
  double distance = 0.1;  ///< world units, per axis of a move
  double degrees = 5.0;   ///< of a turn
  double factor = 0.1;    ///< of a scale factor
};

/// The maths of one modal transform (G / R / S): the world motion of a selection about a pivot
/// from the pointer ray, an axis constraint, a typed value and snapping. Computed from the start
/// ray each time (no drift; the rule for gestures of widget-model.md).
/// - Move: free, in the view plane through the pivot; along an axis, by the closest point of the
///   axis line to the ray; in a plane (excluded axis), by the ray's hit of that plane. Typed:
///   one number moves along the constraint axis (x when free), "a,b,c" by that vector.
/// - Rotate: by the angle the pointer turns about the pivot as seen in the view, about the view
///   axis, or about the constraint axis (sign chosen so that the turn follows the pointer).
///   Typed: degrees, counter-clockwise about +axis (the view axis pointing at the viewer when free).
/// - Scale: by the ratio of the pointer's distances from the pivot (now / at the start), all
///   axes, one axis, or the two of a plane. Typed: the factor.
/// Snapping rounds the distance per axis, the angle or the factor to SnapSteps.
class ModalTransform {
 public:
  /// `viewDirection`: from the camera into the scene.
  ModalTransform(TransformMode mode, const Eigen::Vector3d& pivot, const widgets::Ray& startRay,
                 const Eigen::Vector3d& viewDirection, SnapSteps steps = {});

  TransformMode mode() const { return mode_; }
  const Eigen::Vector3d& pivot() const { return pivot_; }
  AxisConstraint constraint() const { return constraint_; }
  void setConstraint(AxisConstraint constraint) { constraint_ = constraint; }
  TypedValue& typed() { return typed_; }
  const TypedValue& typed() const { return typed_; }

  /// The world motion for the pointer at `ray` (or the typed value, when one is typed).
  Eigen::Affine3d motion(const widgets::Ray& ray, bool snap);
  /// The last motion's amount as a designer reads it: "move 0.500 along z", "turn 5.0° about z",
  /// "scale x1.200".
  std::string describe() const;

 private:
  Eigen::Affine3d about(const Eigen::Matrix3d& linear) const;
  Eigen::Vector3d rotationAxis() const;
  std::optional<Eigen::Vector3d> moveHit(const widgets::Ray& ray) const;

  TransformMode mode_;
  Eigen::Vector3d pivot_;
  widgets::Ray start_;
  Eigen::Vector3d view_;
  SnapSteps steps_;
  AxisConstraint constraint_;
  TypedValue typed_;
  // The last values (kept when a ray is parallel to the drag line or plane).
  Eigen::Vector3d distance_ = Eigen::Vector3d::Zero();
  double angle_ = 0.0, lastRaw_ = 0.0, factor_ = 1.0;
  AxisConstraint angleFor_;  ///< the constraint the unwrapped angle was measured under
};

}  // namespace ffdkit::app
