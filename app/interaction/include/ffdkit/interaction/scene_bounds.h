#pragma once

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/widgets/widget_id.h"

namespace ffdkit::app {

/// The world box of `widgets` and `objects` as drawn: a lattice's control points, a cell's
/// points, an affine widget's glyph (its frame's origin +- its glyph size), an object's deformed
/// points (SceneDeformer::points). Empty when there is nothing (unknown names are skipped).
Eigen::AlignedBox3d selectionBounds(const scenes::Scene& scene, const scenes::SceneDeformer& deformed,
                                    const std::vector<widgets::WidgetId>& widgets,
                                    const std::vector<std::string>& objects);

/// The world box of everything drawn: every object (deformed), every lattice and widget.
Eigen::AlignedBox3d sceneBounds(const scenes::Scene& scene, const scenes::SceneDeformer& deformed);

}  // namespace ffdkit::app
