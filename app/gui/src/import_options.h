// File > Import Up Axis: the up axis mesh files are read with (scenes/up_axis.h), a preference
// kept between sessions.
#pragma once

#include "ffdkit/scenes/up_axis.h"

class QMenu;

namespace ffdkit::app {

/// QSettings key of the import up axis: "z" (default: the file's coordinates as they are) or "y".
inline constexpr const char* kImportUpAxisKey = "importUpAxis";

/// Adds the Import Up Axis submenu to `file`: Z Up / Y Up (object names actionImportZUp,
/// actionImportYUp), exclusive, checked from and saved to QSettings.
void addImportUpAxisMenu(QMenu* file);

/// The up axis the next import reads files with.
scenes::UpAxis importUpAxis();

}  // namespace ffdkit::app
