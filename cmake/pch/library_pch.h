#pragma once

// Precompiled for the core libraries in clang sanitizer builds (cmake/FfdkitOptions.cmake,
// ffdkit_precompile_headers SHARED): the standard library and Eigen headers that their files
// include. A file compiles as if it included them all, so it must not rely on their absence
// (the GCC and fuzz builds compile it without them).

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
