// STEP and IGES parts in the app (docs/cad.md): File > Import Mesh reads them as objects (their
// tessellation, deformed live like any mesh), File > Export Deformed CAD Model writes the exact
// FFD of the B-rep (cad::deformCad). The reading and writing are cad_scene's
// (ffdkit/cad_scene/scene_cad_objects.h, shared with ffdkit-cli); here the Qt side: the
// tessellation setting, its dialog, the export's choice of object and its status line. Without
// the cad module (FFDKIT_WITH_CAD=OFF) both say that the build lacks it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <QString>

#include "ffdkit/scenes/scene.h"

class QMenu;
class QWidget;

namespace ffdkit::app {

/// QSettings key of the import tessellation tolerance: the largest distance between a triangle
/// and its face, relative to the part's bounding-box diagonal (default 1e-3).
inline constexpr const char* kCadTessellationKey = "cadTessellationTolerance";

/// Whether this build has the cad module (OpenCASCADE).
bool hasCadModule();

/// Registers the reader of STEP and IGES objects (cad_scene::registerCadObjectReader) with the
/// import tolerance of the moment (cadTessellationTolerance) and cad_scene's other defaults.
/// Without the cad module it registers nothing (such objects are read errors that say so).
void registerCadObjectReader();

/// The import tessellation tolerance (relative to the part's size), from QSettings; the default
/// (cad_scene::CadObjectTessellation) when unset or out of range.
double cadTessellationTolerance();

/// Adds File > CAD Tessellation Tolerance... (actionCadTessellation): asks for the relative
/// tolerance (1e-6 .. 0.1) and keeps it for the next imports; a part already open keeps its
/// triangles.
void addCadTessellationAction(QMenu* file, QWidget* parent);

/// File > Export Deformed CAD Model: the CAD object among `selected` (else the scene's only CAD
/// object) deformed exactly (cad::CadMethod::Exact) by the one lattice attached to it, written
/// as STEP or IGES by the extension of `output` (cad_scene::writeDeformedCadObject); undeformed
/// (no lattice) it is written as read. `baseDirectory` resolves a relative source path (the scene
/// file's folder).
/// @return the status line's report. @throws std::runtime_error (cad::CadError, ...) saying what
///         stops the export: no CAD object, more than one lattice or a child lattice, a lattice or
///         outside policy the exact composition cannot take, a degree over its limit, a build
///         without CAD; nothing is written then.
QString exportDeformedCad(const scenes::Scene& scene, const std::vector<std::string>& selected,
                          const std::filesystem::path& baseDirectory, const std::filesystem::path& output);

}  // namespace ffdkit::app
