#pragma once

#include <Eigen/Geometry>

#include "ffdkit/scenes/scene.h"

namespace ffdkit::app {

/// The 3D view's camera as navigation changes it: the scene's camera (position, focal point,
/// view up, view angle, world coordinates) and the projection.
struct ViewCamera {
  scenes::Camera camera;
  bool parallel = false;       ///< orthographic projection
  double parallelScale = 1.0;  ///< when parallel: half the view's height in world units (> 0)
};

/// How a drag on empty space turns the camera about its focal point.
enum class OrbitStyle {
  /// Left-right turns about the world's up axis, up-down tilts about the camera's horizontal
  /// axis (kept within 0.1 degrees of straight up or down): the horizon never rolls (Blender's
  /// and Maya's default).
  Turntable,
  /// Left-right turns about the camera's own up, up-down about its horizontal axis, both carried
  /// by the camera (VTK's trackball camera): free, but a closed path of the pointer can leave
  /// the view rolled.
  Trackball,
};

struct OrbitOptions {
  OrbitStyle style = OrbitStyle::Turntable;
  Eigen::Vector3d worldUp = Eigen::Vector3d::UnitZ();  ///< the turntable's axis (ffdkit's world is Z-up)
  double degreesPerPixel = 0.4;
};

/// The camera after the pointer moved (dx, dy) pixels (x right, y down, as on screen) while
/// orbiting: the scene turns with the pointer as if grabbed (right: its front moves right; down:
/// its top comes toward the viewer). Focal point, distance and projection stay.
ViewCamera orbit(const ViewCamera& view, double dx, double dy, const OrbitOptions& options = {});

/// Options of frame().
struct FrameOptions {
  double aspect = 1.0;   ///< the view's width / height (> 0)
  double margin = 1.05;  ///< the bounding sphere's radius is enlarged by this factor
};

/// The camera that shows `box` whole, looking the way `view` looks: the focal point goes to the
/// box's centre and the distance (perspective) or the parallel scale (orthographic) is the least
/// at which the box's bounding sphere (times `margin`) fits in both the vertical and the
/// horizontal field of view. A point (empty extent) is shown at the current distance.
/// @throws std::invalid_argument for an empty box or a non-positive aspect.
ViewCamera frame(const ViewCamera& view, const Eigen::AlignedBox3d& box, const FrameOptions& options = {});

/// The axis views of the keypad (Blender's numpad), for ffdkit's Z-up world.
enum class ViewPreset {
  Front,   ///< looking along +y (from -y), z up
  Back,    ///< looking along -y, z up
  Right,   ///< looking along -x (from +x), z up
  Left,    ///< looking along +x, z up
  Top,     ///< looking along -z (from above), y up
  Bottom,  ///< looking along +z, -y up
};

/// The direction of view (from the camera to its focal point) and the view up of a preset.
std::pair<Eigen::Vector3d, Eigen::Vector3d> viewPresetAxes(ViewPreset preset);

/// `view` turned to look along the preset's direction, about the same focal point at the same
/// distance and projection.
ViewCamera viewFrom(const ViewCamera& view, ViewPreset preset);

/// Perspective <-> orthographic, keeping the size things at the focal point appear: going
/// parallel, the scale is distance * tan(angle / 2); going back, the distance is
/// scale / tan(angle / 2) (a zoom made in parallel is kept).
ViewCamera toggledProjection(const ViewCamera& view);

}  // namespace ffdkit::app
