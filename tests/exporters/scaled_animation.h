#pragma once
// Test support: an animation of a sample scene without keys in its file: every affine widget's
// variation in the given scene scaled by the time (t = 0: rest, t = 1: that pose), set from rest
// each time (so the state depends on t only). The keyed samples store their rest pose (frame 0):
// the tests take them to a later frame first (gltf_export_test.cpp, posed()).

#include <utility>
#include <vector>

#include "ffdkit/exporters/gltf_export.h"
#include "ffdkit/scenes/scene.h"

namespace ffdkit::exporters::test {

inline AnimationSource scaledVariations(const scenes::Scene& scene, std::vector<double> keys = {0.0, 0.5, 1.0},
                                        KeyInterpolation interpolation = KeyInterpolation::Linear) {
  std::vector<std::pair<widgets::WidgetId, double>> saved;
  for (const widgets::WidgetId id : scene.widgets.widgets(widgets::WidgetType::Affine))
    saved.emplace_back(id, scene.widgets.variation(id));
  AnimationSource source;
  source.keyTimes = std::move(keys);
  source.interpolation.assign(source.keyTimes.size(), interpolation);
  source.frameRate = 8.0;
  source.setTime = [saved, interpolation, times = source.keyTimes](scenes::Scene& s, double t) {
    if (interpolation == KeyInterpolation::Constant) {  // the last key at or before t
      double held = times.front();
      for (double k : times)
        if (k <= t) held = k;
      t = held;
    }
    for (const auto& [id, value] : saved) s.widgets.setVariation(id, 0.0);
    for (const widgets::WidgetId lattice : s.widgets.pipelineOrder()) s.widgets.resetLattice(lattice);
    for (const auto& [id, value] : saved) s.widgets.setVariation(id, value * t);
  };
  return source;
}

}  // namespace ffdkit::exporters::test
