#pragma once

#include <string>

#include "ffdkit/cad/cad_model.h"

namespace ffdkit::cad {

/// What checkModel() found.
struct CadCheck {
  bool valid = true;         ///< every part passes OpenCASCADE's BRepCheck_Analyzer
  std::string firstProblem;  ///< "part 'x': <shape> <index>: <BRepCheck status>" of the first invalid shape (for a face, with the wire or edge rejected on it), or empty
  double volume = 0.0;       ///< sum of the parts' volumes (BRepGProp), 0 for parts without solids
  double maxTolerance = 0.0; ///< the largest vertex, edge or face tolerance of the model
};

/// Checks every part with BRepCheck_Analyzer and measures its volume (BRepGProp, relative
/// precision 1e-9). @throws CadError if OpenCASCADE throws while checking.
CadCheck checkModel(const CadModel& model);

}  // namespace ffdkit::cad
