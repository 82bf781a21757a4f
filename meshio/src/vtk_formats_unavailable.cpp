// .vtp and legacy .vtk writing in a build without VTK (FFDKIT_WITH_VTK=OFF): meshio still reads
// both (vtp_format.cpp, legacy_vtk_format.cpp, which need no VTK); writing them needs VTK's
// writers (vtk_formats.cpp), so it is refused with a clear error (ffdkit/meshio/vtk_writer.h).
#include "ffdkit/meshio/vtk_writer.h"

namespace ffdkit::meshio {

std::string vtkPolyDataBytes(const MeshData&, bool xml) {
  throw MeshIoError(std::string("writing ") + (xml ? ".vtp" : "legacy .vtk") +
                    " needs VTK, and this ffdkit was built without it (FFDKIT_WITH_VTK=OFF); "
                    "write .ply, .obj, .stl, .glb or .npy instead");
}

}  // namespace ffdkit::meshio
