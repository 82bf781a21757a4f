#pragma once
// The writer of VTK poly data (.vtp and legacy .vtk) that writeMesh calls, and how a program
// replaces it.

#include <string>

#include "ffdkit/meshio/mesh_data.h"

namespace ffdkit::meshio {

/// The bytes of `mesh` as VTK XML poly data (`xml`, .vtp) or legacy VTK poly data (.vtk): what
/// writeMesh writes for those two formats. meshio defines it in an object file of its own, through
/// VTK's writers (or, built without VTK, as a MeshIoError saying so). A program that links meshio
/// statically may define this function itself: the linker then takes the program's definition and
/// leaves meshio's out, and with it every reference to VTK (ffdkit-cli does so to load VTK only
/// when a command writes one of these formats, docs/cli.md).
/// @throws MeshIoError when the mesh cannot be written.
std::string vtkPolyDataBytes(const MeshData& mesh, bool xml);

}  // namespace ffdkit::meshio
