#pragma once
// A scene's CAD objects (STEP and IGES parts a scene names like mesh files; docs/cad.md), as the
// app and ffdkit-cli both handle them: read as triangles (the B-rep tessellated), and written back
// as the B-rep deformed exactly by the one lattice attached. One home for the tessellation every
// program shows, for the lattice rule and for what a build without OpenCASCADE says. This library
// is built with or without the cad module (FFDKIT_WITH_CAD): its header holds no cad type, and
// without the module its readers and writers throw CadUnavailableError.

#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "ffdkit/meshio/read_limits.h"
#include "ffdkit/scenes/mesh_io.h"
#include "ffdkit/scenes/scene.h"

namespace ffdkit::cad_scene {

/// Whether this build has the cad module (OpenCASCADE, FFDKIT_WITH_CAD).
bool builtWithCad();

/// What a build without the cad module throws when asked to read or write STEP or IGES: "this
/// program was built without OpenCASCADE (FFDKIT_WITH_CAD=OFF), which <what> need".
class CadUnavailableError : public std::runtime_error {
 public:
  /// `what` names what needs the module ("STEP and IGES inputs").
  explicit CadUnavailableError(const std::string& what);
};

/// The smallest and largest tessellation tolerance a program offers (relative to the part's size).
inline constexpr double kSmallestTessellationTolerance = 1e-6;
/// See kSmallestTessellationTolerance.
inline constexpr double kLargestTessellationTolerance = 0.1;

/// How a scene's CAD object is tessellated when read, relative to the part's size (the diagonal
/// of its bounding box).
struct CadObjectTessellation {
  /// The largest distance between a triangle and its face (BRepMesh's linear deflection).
  double tolerance = 1e-3;
  /// The longest triangle edge: BRepMesh gives a plane the points of its boundary only, which a
  /// lattice would bend as flat triangles, so the longest edges are bisected down to this.
  double maxEdgeLength = 0.02;
};

/// Reads the STEP or IGES file `path` (cad::readCad: in a child process, with its time and memory
/// limits) and tessellates it as `tessellation` says; charges the points and triangles to `budget`.
/// @return the triangles (points N x 3, in the part's own axes).
/// @throws cad::CadError naming the file for a bad file, meshio's budget error naming the file
///         when the tessellation exceeds `budget`, CadUnavailableError without the cad module.
scenes::MeshData readCadObject(const std::filesystem::path& path, meshio::ReadBudget& budget,
                               const CadObjectTessellation& tessellation = {});

/// Registers readCadObject as this process's reader of scenes' CAD objects
/// (scenes::setCadMeshReader), with the tessellation `tessellation()` gives at each read (the
/// app's setting may change between imports); an empty function gives the defaults. Without the
/// cad module it registers nothing, and a scene naming a CAD file is a read error saying so.
void registerCadObjectReader(std::function<CadObjectTessellation()> tessellation = {});

/// Whether `object` is read from a STEP or IGES file (a mesh file source with a CAD extension).
bool isCadObject(const scenes::SceneObject& object);

/// The scene's CAD objects, in scene order.
std::vector<const scenes::SceneObject*> cadObjects(const scenes::Scene& scene);

/// The file of a CAD object: its source path, resolved against `baseDirectory` (the scene file's
/// folder) when relative. @pre isCadObject(object).
std::filesystem::path cadObjectFile(const scenes::SceneObject& object, const std::filesystem::path& baseDirectory);

/// The lattice that deforms `object` in a STEP or IGES output: none when no lattice is attached.
/// @throws std::runtime_error naming the object when more than one lattice is attached, or its
///         lattice has child lattices (an exact output composes one lattice).
std::optional<widgets::WidgetId> cadObjectLattice(const scenes::Scene& scene, const scenes::SceneObject& object);

/// What writeDeformedCadObject wrote: the cad module's report (cad::CadDeformReport), in short.
struct CadObjectExport {
  std::string lattice;             ///< the lattice that deformed the part; empty: written as read
  int faces = 0;                   ///< faces deformed
  int maxDegree = 0;               ///< the highest degree of a deformed surface or curve
  int approximatedFaces = 0;       ///< faces approximated to `tolerance` (the rest composed exactly)
  int approximatedEdges = 0;       ///< edges approximated to `tolerance`
  double tolerance = 0.0;          ///< the approximations' tolerance (model units; 0 without any)
  double approximationError = 0.0; ///< the largest deviation of an approximation measured
};

/// Reads `object`'s file again (cadObjectFile) and writes it to `output` (STEP or IGES by the
/// extension) deformed by its lattice (cadObjectLattice) with cad::deformCad's default options, at
/// the lattice's present control points; undeformed, as read, when no lattice is attached.
/// @throws std::runtime_error (cad::CadError, ...) saying what stops it: an output that is not
///         STEP or IGES, the lattice rule above, a deformation the cad module refuses (its message
///         then ends "Nothing was exported."), CadUnavailableError without the cad module; nothing
///         is written then.
CadObjectExport writeDeformedCadObject(const scenes::Scene& scene, const scenes::SceneObject& object,
                                       const std::filesystem::path& baseDirectory,
                                       const std::filesystem::path& output);

}  // namespace ffdkit::cad_scene
