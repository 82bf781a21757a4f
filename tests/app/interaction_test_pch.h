#pragma once

// Precompiled once for the headless GoogleTest programs of the interaction library
// (tests/app/CMakeLists.txt, ffdkit_add_interaction_test): GoogleTest, Eigen and the
// interaction and scene headers most of them include. A program compiles as if it included them
// all, so it must not rely on their absence.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/interaction/edit_controller.h"
#include "ffdkit/interaction/interaction_controller.h"
#include "ffdkit/interaction/timeline.h"
#include "ffdkit/scenes/animation.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"
