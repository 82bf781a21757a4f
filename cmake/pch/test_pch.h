#pragma once

// Precompiled for the core libraries' GoogleTest programs in clang sanitizer builds
// (cmake/FfdkitOptions.cmake, ffdkit_precompile_headers SHARED): GoogleTest and the standard
// library and Eigen headers that their files include. A file compiles as if it included them all,
// so it must not rely on their absence (the GCC and fuzz builds compile it without them).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
