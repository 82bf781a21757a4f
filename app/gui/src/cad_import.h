// STEP and IGES parts in the app (docs/cad.md): File > Import Mesh reads them as objects (their
// tessellation, deformed live like any mesh), File > Export Deformed CAD Model writes the exact
// FFD of the B-rep (cad::deformCad). Without the cad module (FFDKIT_WITH_CAD=OFF) both say that
// the build lacks it.
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

/// Registers the reader of STEP and IGES objects (scenes::setCadMeshReader): the part read by
/// cad::readCad (in a child process, with its time and memory limits) and tessellated with the
/// import tolerance, no triangle edge longer than 2% of the part's size. Without the cad module it registers nothing (such objects are read errors
/// that say the build lacks CAD).
void registerCadObjectReader();

/// The import tessellation tolerance (relative to the part's size), from QSettings.
double cadTessellationTolerance();

/// Adds File > CAD Tessellation Tolerance... (actionCadTessellation): asks for the relative
/// tolerance (1e-6 .. 0.1) and keeps it for the next imports; a part already open keeps its
/// triangles.
void addCadTessellationAction(QMenu* file, QWidget* parent);

/// File > Export Deformed CAD Model: the CAD object among `selected` (else the scene's only CAD
/// object) deformed exactly (cad::CadMethod::Exact) by the one lattice attached to it, written
/// as STEP or IGES by the extension of `output`; undeformed (no lattice) it is written as read.
/// `baseDirectory` resolves a relative source path (the scene file's folder).
/// @return the status line's report. @throws std::runtime_error (cad::CadError, ...) saying what
///         stops the export: no CAD object, more than one lattice or a child lattice, a lattice or
///         outside policy the exact composition cannot take, a degree over its limit, a build
///         without CAD; nothing is written then.
QString exportDeformedCad(const scenes::Scene& scene, const std::vector<std::string>& selected,
                          const std::filesystem::path& baseDirectory, const std::filesystem::path& output);

}  // namespace ffdkit::app
