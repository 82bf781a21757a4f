#pragma once

namespace ffdkit::widgets {

/// The default glyph shapes (Kuriyama 1996, sec. 6.4: arrow = translate, ring = rotate, cube =
/// scale) in glyph sizes (WidgetFrame::size, the widget frame's axes): the one home of the
/// glyph-size mapping, so that what WidgetModel::pick hits is what app::SceneView draws.
struct GlyphShape {
  /// The arrow runs from the widget's origin along +x for this many sizes.
  static constexpr double arrowLength = 1.0;
  static constexpr double arrowShaftRadius = 0.04;  ///< shaft radius
  static constexpr double arrowTipRadius = 0.1;  ///< tip cone radius
  static constexpr double arrowTipLength = 0.25;  ///< tip cone length
  /// The ring lies in the widget's xy plane about z.
  static constexpr double ringRadius = 1.0;
  static constexpr double ringTubeRadius = 0.05;  ///< tube radius
  /// The cube is centred on the origin.
  static constexpr double cubeHalfWidth = 0.15;
  /// How far beyond the pick tolerance a ray may pass an arrow or a ring and still hit it: the
  /// drawn shaft and tube thickness.
  static constexpr double pickThickness = 0.05;
};

}  // namespace ffdkit::widgets
