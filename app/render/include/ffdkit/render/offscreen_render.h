#pragma once

#include <filesystem>

#include "ffdkit/scenes/scene.h"

namespace ffdkit::app {

struct OffscreenRenderOptions {
  int width = 1024;   ///< pixels
  int height = 768;   ///< pixels
};

/// Renders `scene` off screen (needs an X display or Xvfb for Mesa's GL) and writes a PNG.
/// The PNG is written atomically. @throws std::runtime_error if rendering or writing fails.
void renderSceneToPng(const scenes::Scene& scene, const std::filesystem::path& png,
                      const OffscreenRenderOptions& options = {});

}  // namespace ffdkit::app
