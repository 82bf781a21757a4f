#include "ffdkit/cad/cad_check.h"

#include <algorithm>

#include <BRepCheck_Analyzer.hxx>
#include <BRepCheck_ListOfStatus.hxx>
#include <BRepCheck_Result.hxx>
#include <BRepCheck_Status.hxx>
#include <BRepGProp.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <TopAbs.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>

#include "cad_model_data.h"

namespace ffdkit::cad {

namespace {

const char* shapeTypeName(TopAbs_ShapeEnum type) {
  switch (type) {
    case TopAbs_COMPOUND: return "compound";
    case TopAbs_COMPSOLID: return "compsolid";
    case TopAbs_SOLID: return "solid";
    case TopAbs_SHELL: return "shell";
    case TopAbs_FACE: return "face";
    case TopAbs_WIRE: return "wire";
    case TopAbs_EDGE: return "edge";
    case TopAbs_VERTEX: return "vertex";
    default: return "shape";
  }
}

/// The first sub-shape the analyzer rejects, with its BRepCheck status number.
std::string firstInvalid(const BRepCheck_Analyzer& analyzer, const TopoDS_Shape& shape) {
  for (TopAbs_ShapeEnum type : {TopAbs_VERTEX, TopAbs_EDGE, TopAbs_WIRE, TopAbs_FACE, TopAbs_SHELL, TopAbs_SOLID}) {
    int index = 0;
    for (TopExp_Explorer it(shape, type); it.More(); it.Next()) {
      ++index;
      const Handle(BRepCheck_Result) result = analyzer.Result(it.Current());
      if (result.IsNull()) continue;
      for (BRepCheck_ListIteratorOfListOfStatus status(result->Status()); status.More(); status.Next())
        if (status.Value() != BRepCheck_NoError)
          return std::string(shapeTypeName(type)) + " " + std::to_string(index) + ": BRepCheck status " +
                 std::to_string(static_cast<int>(status.Value()));
    }
  }
  return "invalid (no sub-shape status recorded)";
}

}  // namespace

CadCheck checkModel(const CadModel& model) {
  CadCheck check;
  for (const auto& part : model.data().parts) {
    guardOcct("checking part '" + part.name + "'", [&] {
      BRepCheck_Analyzer analyzer(part.shape);
      if (!analyzer.IsValid() && check.valid) {
        check.valid = false;
        check.firstProblem = "part '" + part.name + "': " + firstInvalid(analyzer, part.shape);
      }
      for (TopExp_Explorer it(part.shape, TopAbs_SOLID); it.More(); it.Next()) {
        GProp_GProps props;
        BRepGProp::VolumeProperties(it.Current(), props, 1e-9, true);
        check.volume += props.Mass();
      }
      for (TopExp_Explorer it(part.shape, TopAbs_VERTEX); it.More(); it.Next())
        check.maxTolerance = std::max(check.maxTolerance, BRep_Tool::Tolerance(TopoDS::Vertex(it.Current())));
      for (TopExp_Explorer it(part.shape, TopAbs_EDGE); it.More(); it.Next())
        check.maxTolerance = std::max(check.maxTolerance, BRep_Tool::Tolerance(TopoDS::Edge(it.Current())));
      for (TopExp_Explorer it(part.shape, TopAbs_FACE); it.More(); it.Next())
        check.maxTolerance = std::max(check.maxTolerance, BRep_Tool::Tolerance(TopoDS::Face(it.Current())));
    });
  }
  return check;
}

}  // namespace ffdkit::cad
