#pragma once

#include <string_view>

#include <Eigen/Core>

#include "ffdkit/scenes/mesh_io.h"

namespace ffdkit::scenes {

/// The up axis a mesh file was written with. ffdkit's world is Z-up; OBJ files from many
/// modellers and every glTF file (the glTF 2.0 specification, sec. 3.4: "+Y up, +Z forward") are Y-up.
enum class UpAxis { Z, Y };

/// "z" / "y" (the scene file's `up` key).
std::string_view upAxisName(UpAxis axis);

/// The rotation from a file's coordinates to ffdkit's Z-up world: identity for Z; for Y a turn
/// of +90 degrees about x, (x, y, z) -> (x, -z, y), so the file's +y (up) becomes +z and its +z
/// (a glTF asset's front) becomes -y, the side the Front view (numpad 1) looks at. A proper
/// rotation: lengths, angles and the triangles' orientation are kept.
Eigen::Matrix3d upAxisRotation(UpAxis axis);

/// Turns the points of a mesh read from a file written `axis`-up to ffdkit's Z-up world, in
/// place (#P x 3 rows). Triangles and segments keep their indices.
void convertToZUp(MeshData& mesh, UpAxis axis);

}  // namespace ffdkit::scenes
