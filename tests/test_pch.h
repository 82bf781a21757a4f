#pragma once

// Precompiled in clang builds (the sanitizer and fuzz stages) for the test programs
// (tests/CMakeLists.txt, ffdkit_add_test): GoogleTest, Eigen and the standard library headers that
// most test files include. Third-party headers only, so that one precompiled header serves every
// program with the same compile flags. A test file compiles as if it included these first, so it
// must not rely on their absence.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <gtest/gtest.h>
