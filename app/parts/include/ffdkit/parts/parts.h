#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ffdkit/geometry/tessellation.h"

namespace ffdkit::app {

/// The parts library (Kuriyama 1996, sec. 6.4): shapes that replace an affine widget's default glyph
/// (Glyph::shape names a part). Each part is built procedurally from primitives, fits the
/// box [-0.5, 0.5]^3 before the glyph's size scales it, and has its handle axis along +x
/// (translate, lever) or its turning axis along +z (crank, screw, wheel), like the glyphs.
std::vector<std::string> partNames();  ///< "crank", "lever", "screw", "wheel"

/// The part's triangle mesh (unit size, in the widget's frame), or nullopt for an unknown name.
std::optional<geometry::TriangleMesh> partMesh(std::string_view name);

}  // namespace ffdkit::app
