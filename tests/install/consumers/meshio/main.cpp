// ffdkit::meshio from an installed package: a tetrahedron written as PLY and as OBJ into the
// folder given and read back holds the same points (values exact in float32 and in text) and
// triangles; a file with a face naming a missing vertex is refused with the file in the message.
// Usage: consumer <folder>.
#include <filesystem>
#include <fstream>
#include <string>

#include "../consumer_check.h"
#include "ffdkit/meshio/mesh_io.h"

using namespace ffdkit;

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const std::filesystem::path folder = argv[1];
  meshio::MeshData tetrahedron;
  tetrahedron.points.resize(4, 3);
  tetrahedron.points << 0.0, 0.0, 0.0,  //
      1.0, 0.0, 0.0,                    //
      0.0, 0.5, 0.0,                    //
      0.0, 0.0, 0.25;
  tetrahedron.triangles.resize(4, 3);
  tetrahedron.triangles << 0, 2, 1,  //
      0, 1, 3,                       //
      1, 2, 3,                       //
      0, 3, 2;
  for (const char* name : {"tetrahedron.ply", "tetrahedron.obj"}) {
    meshio::writeMesh(folder / name, tetrahedron);
    const meshio::MeshData back = meshio::readMesh(folder / name);
    consumer::check(back.points == tetrahedron.points && back.triangles == tetrahedron.triangles,
                    (std::string(name) + " round-trips").c_str());
  }
  std::ofstream(folder / "bad.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n";
  try {
    meshio::readMesh(folder / "bad.obj");
    consumer::check(false, "a face naming vertex 7 of 3 is refused");
  } catch (const meshio::MeshIoError& e) {
    consumer::check(std::string(e.what()).find("bad.obj") != std::string::npos, "a face naming vertex 7 of 3 is refused");
  }
  return consumer::exitCode();
}
