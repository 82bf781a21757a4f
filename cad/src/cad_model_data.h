#pragma once

#include <string>
#include <vector>

#include <Standard_Failure.hxx>
#include <TopoDS_Shape.hxx>

#include "ffdkit/cad/cad_error.h"
#include "ffdkit/cad/cad_model.h"

namespace ffdkit::cad {

/// One part: its name and its shape, placed in the world (the shape's location is the placement).
struct CadPartData {
  std::string name;
  TopoDS_Shape shape;
};

/// The parts of a CadModel.
struct CadModelData {
  std::vector<CadPartData> parts;
};

/// "what: <OpenCASCADE's exception type and message>", for CadError messages.
std::string describeFailure(const std::string& what, const Standard_Failure& failure);

/// Runs `body`, turning OpenCASCADE's exceptions into a CadError "<context>: <failure>".
template <class Body>
auto guardOcct(const std::string& context, Body&& body) -> decltype(body()) {
  try {
    return body();
  } catch (const CadError&) {
    throw;
  } catch (const Standard_Failure& failure) {
    throw CadError(describeFailure(context, failure));
  }
}

}  // namespace ffdkit::cad
