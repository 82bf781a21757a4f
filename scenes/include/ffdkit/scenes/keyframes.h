#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ffdkit/widgets/widget_id.h"

namespace ffdkit::scenes {

/// How a channel's value goes from one key to the next (the key's own setting governs the
/// segment that starts at it; after the last key, and before the first, the value holds).
enum class Interpolation {
  Constant,  ///< holds the key's value until the next key (a step)
  Linear,    ///< straight to the next key's value (rotations of a frame: slerp)
  /// A cubic Hermite segment whose tangents are set automatically: Catmull-Rom (finite
  /// difference) slopes (p[i+1] - p[i-1]) / (t[i+1] - t[i-1]), flattened to 0 at a local extremum
  /// and at the first and last key, like Blender's "Auto Clamped" handles: the curve passes
  /// through every key, is C1 at interior keys and never overshoots an extremum. See
  /// evaluateSmooth (animation.h) for the formula.
  Smooth
};

/// What a channel animates on its widget.
enum class ChannelKind {
  Variation,     ///< an affine widget's variation (distance, rad, log scale): set through a gesture
  LatticeFrame,  ///< a lattice's world frame (root lattices and one-way child lattices)
  ControlPoints  ///< a lattice's local control points (pointCount x 3)
};

/// One key of a channel. Only the value of the channel's kind is used.
struct Keyframe {
  double time = 0.0;  ///< seconds
  Interpolation interpolation = Interpolation::Smooth;  ///< of the segment from this key to the next
  double variation = 0.0;                                ///< ChannelKind::Variation
  Eigen::Affine3d frame = Eigen::Affine3d::Identity();   ///< ChannelKind::LatticeFrame: world = frame * local
  Eigen::MatrixX3d points;                               ///< ChannelKind::ControlPoints: local, pointCount x 3

  friend bool operator==(const Keyframe& a, const Keyframe& b) {  ///< equal when every field is (the matrices compared entry by entry)
    return a.time == b.time && a.interpolation == b.interpolation && a.variation == b.variation &&
           a.frame.matrix() == b.frame.matrix() && a.points.rows() == b.points.rows() && a.points == b.points;
  }
};

/// The keys of one property of one widget, strictly increasing in time.
struct Channel {
  widgets::WidgetId widget;  ///< the keyed widget (an affine widget or a lattice)
  ChannelKind kind = ChannelKind::Variation;  ///< which property is keyed
  std::vector<Keyframe> keys;  ///< strictly increasing in time
};

/// Limits a scene's animation must keep (files are untrusted input: a reader refuses more).
inline constexpr std::size_t kMaxChannels = 10'000;
inline constexpr std::size_t kMaxKeysPerChannel = 100'000;
inline constexpr std::size_t kMaxKeyValues = 50'000'000;  ///< numbers held by all keys together
inline constexpr double kMaxFrameRate = 1000.0;           ///< frames per second
inline constexpr int kMaxFrameMagnitude = 10'000'000;     ///< |first|, |last| frame
inline constexpr double kMaxKeyTime = 1.0e7;              ///< |time| in seconds

/// A scene's animation: a frame rate, a frame range and keyed channels. Frame f is at time
/// f / framesPerSecond seconds.
struct Animation {
  double framesPerSecond = 24.0;  ///< (0, kMaxFrameRate]
  int firstFrame = 0;             ///< first <= last
  int lastFrame = 72;  ///< last frame of the range
  /// Evaluated in this order within each kind (applyAnimation, animation.h); at most one channel
  /// per widget and kind.
  std::vector<Channel> channels;

  /// True when nothing is keyed.
  bool empty() const { return channels.empty(); }
};

}  // namespace ffdkit::scenes
