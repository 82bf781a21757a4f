#pragma once

// Precompiled in clang builds (the sanitizer and fuzz stages) for the libraries
// (cmake/FfdkitOptions.cmake, ffdkit_add_module_library): Eigen and the standard library headers
// that most of their files include. Third-party headers only: a project header's meaning can
// depend on the target that includes it. A file compiles as if it included these first, so it
// must not rely on their absence (nor configure Eigen by macros of its own).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
