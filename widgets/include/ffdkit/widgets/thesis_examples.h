#pragma once

#include <optional>

#include "ffdkit/widgets/widget_model.h"

namespace ffdkit::widgets {

/// The deformation tools of the figures of Kuriyama 1996, sec. 6.5, built with the scripting API.
/// Tests reproduce the figures from them, widgets/examples/*.json hold them as widget files,
/// and the app can offer them as starting points. Each returns the model and the ids a script
/// needs.

/// Fig. 6-2: a 3x3x3 lattice in the unit box with a rotate widget on the face (0,0,2)/normal z,
/// a translate widget (+x) on the edge (0,2,0)/x and a translate widget (+z) on the point (2,2,0).
struct Fig62 {
  WidgetModel model;         ///< the tool
  WidgetId lattice;          ///< the 3x3x3 lattice
  WidgetId face;             ///< the face cell (0,0,2), normal z
  WidgetId edge;             ///< the edge cell (0,2,0) along x
  WidgetId point;            ///< the point cell (2,2,0)
  WidgetId faceRotate;       ///< the rotate widget on the face
  WidgetId edgeTranslate;    ///< the translate widget (+x) on the edge
  WidgetId pointTranslate;   ///< the translate widget (+z) on the point
};
Fig62 buildFig62();

/// Fig. 6-8: a 2x3x2 lattice; on the two faces with normal y (j = 0 and j = 2) translate widgets
/// pointing outwards and rotate widgets about +y; on the edges (0,0,1)/x and (0,2,1)/x translate
/// widgets pointing outwards. Each pair is bound with gain 1: mirror symmetry about y = 0.5.
struct Fig68 {
  WidgetModel model;        ///< the tool
  WidgetId lattice;         ///< the 2x3x2 lattice
  WidgetId faceA;           ///< the face j = 0
  WidgetId faceB;           ///< the face j = 2
  WidgetId edgeA;           ///< the edge (0,0,1) along x
  WidgetId edgeB;           ///< the edge (0,2,1) along x
  WidgetId faceTranslateA;  ///< the translate widget on faceA, pointing outwards
  WidgetId faceTranslateB;  ///< the translate widget on faceB, pointing outwards
  WidgetId faceRotateA;     ///< the rotate widget on faceA, about +y
  WidgetId faceRotateB;     ///< the rotate widget on faceB, about +y
  WidgetId edgeTranslateA;  ///< the translate widget on edgeA, pointing outwards
  WidgetId edgeTranslateB;  ///< the translate widget on edgeB, pointing outwards
};
Fig68 buildFig68();

/// Fig. 6-9: a 2x2x2 parent lattice whose top face carries a 2x2x2 child lattice (the box
/// [0.25, 0.75]^2 x [0.75, 1.25], straddling the face z = 1); a translate widget (+z) lifts the face; translate widgets on
/// the points (0,0,0) (-x) and (1,0,0) (+x) are bound; a translate widget (+y) on the parent's
/// edge (0,1,0)/x is bound to one (+y) on the child's edge (0,0,0)/x.
struct Fig69 {
  WidgetModel model;   ///< the tool
  WidgetId parent;     ///< the 2x2x2 parent lattice
  WidgetId child;      ///< the child lattice on the parent's top face
  WidgetId topFace;    ///< the parent's top face cell
  WidgetId faceLift;   ///< the translate widget (+z) on the top face
  WidgetId pointA;     ///< the translate widget (-x) on the point (0,0,0)
  WidgetId pointB;     ///< the translate widget (+x) on the point (1,0,0), bound to pointA
  WidgetId parentEdge; ///< the translate widget (+y) on the parent's edge (0,1,0)
  WidgetId childEdge;  ///< the translate widget (+y) on the child's edge (0,0,0), bound to parentEdge
};
Fig69 buildFig69();

/// Fig. 6-10: a press. A 2x2x2 lattice ("press-frame") with a translate widget pointing down (-z) on
/// its top face and a free rotate widget (the handle, at (0.5, 0.5, 1.5), drawn as the parts
/// library's crank with its knob on the pick circle) bound to it by a screw rule:
/// one turn lowers the face by `pitch`; `clamp` bounds the press's variation.
struct Fig610 {
  WidgetModel model;  ///< the tool
  WidgetId lattice;   ///< the 2x2x2 lattice "press-frame"
  WidgetId topFace;   ///< its top face cell
  WidgetId press;     ///< the translate widget (-z) on the top face
  WidgetId handle;    ///< the free rotate widget (the crank handle)
  BindingId screw;    ///< the screw binding from handle to press
};
Fig610 buildFig610(double pitch = 0.1, std::optional<VariationRange> clamp = std::nullopt);

}  // namespace ffdkit::widgets
