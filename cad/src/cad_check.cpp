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
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
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

const char* statusName(BRepCheck_Status status) {
  switch (status) {
    case BRepCheck_NoError: return "NoError";
    case BRepCheck_InvalidPointOnCurve: return "InvalidPointOnCurve";
    case BRepCheck_InvalidPointOnCurveOnSurface: return "InvalidPointOnCurveOnSurface";
    case BRepCheck_InvalidPointOnSurface: return "InvalidPointOnSurface";
    case BRepCheck_No3DCurve: return "No3DCurve";
    case BRepCheck_Multiple3DCurve: return "Multiple3DCurve";
    case BRepCheck_Invalid3DCurve: return "Invalid3DCurve";
    case BRepCheck_NoCurveOnSurface: return "NoCurveOnSurface";
    case BRepCheck_InvalidCurveOnSurface: return "InvalidCurveOnSurface";
    case BRepCheck_InvalidCurveOnClosedSurface: return "InvalidCurveOnClosedSurface";
    case BRepCheck_InvalidSameRangeFlag: return "InvalidSameRangeFlag";
    case BRepCheck_InvalidSameParameterFlag: return "InvalidSameParameterFlag";
    case BRepCheck_InvalidDegeneratedFlag: return "InvalidDegeneratedFlag";
    case BRepCheck_FreeEdge: return "FreeEdge";
    case BRepCheck_InvalidMultiConnexity: return "InvalidMultiConnexity";
    case BRepCheck_InvalidRange: return "InvalidRange";
    case BRepCheck_EmptyWire: return "EmptyWire";
    case BRepCheck_RedundantEdge: return "RedundantEdge";
    case BRepCheck_SelfIntersectingWire: return "SelfIntersectingWire";
    case BRepCheck_NoSurface: return "NoSurface";
    case BRepCheck_InvalidWire: return "InvalidWire";
    case BRepCheck_RedundantWire: return "RedundantWire";
    case BRepCheck_IntersectingWires: return "IntersectingWires";
    case BRepCheck_InvalidImbricationOfWires: return "InvalidImbricationOfWires";
    case BRepCheck_EmptyShell: return "EmptyShell";
    case BRepCheck_RedundantFace: return "RedundantFace";
    case BRepCheck_InvalidImbricationOfShells: return "InvalidImbricationOfShells";
    case BRepCheck_UnorientableShape: return "UnorientableShape";
    case BRepCheck_NotClosed: return "NotClosed";
    case BRepCheck_NotConnected: return "NotConnected";
    case BRepCheck_SubshapeNotInShape: return "SubshapeNotInShape";
    case BRepCheck_BadOrientation: return "BadOrientation";
    case BRepCheck_BadOrientationOfSubshape: return "BadOrientationOfSubshape";
    case BRepCheck_InvalidPolygonOnTriangulation: return "InvalidPolygonOnTriangulation";
    case BRepCheck_InvalidToleranceValue: return "InvalidToleranceValue";
    case BRepCheck_EnclosedRegion: return "EnclosedRegion";
    case BRepCheck_CheckFail: return "CheckFail";
  }
  return "unknown status";
}

/// The first error status of `result` in the context of `context` (its own statuses when null).
BRepCheck_Status firstError(const Handle(BRepCheck_Result)& result, const TopoDS_Shape* context) {
  if (result.IsNull()) return BRepCheck_NoError;
  if (context && !result->IsStatusOnShape(*context)) return BRepCheck_NoError;
  for (BRepCheck_ListIteratorOfListOfStatus status(context ? result->StatusOnShape(*context) : result->Status());
       status.More(); status.Next())
    if (status.Value() != BRepCheck_NoError) return status.Value();
  return BRepCheck_NoError;
}

/// The first sub-shape the analyzer rejects, with its BRepCheck status; for a face, also the first
/// of its wires and edges rejected on it (an edge off the face, a seam's two p-curves apart: what
/// makes the analyzer call the face unorientable).
std::string firstInvalid(const BRepCheck_Analyzer& analyzer, const TopoDS_Shape& shape) {
  TopTools_IndexedMapOfShape edges, wires;
  TopExp::MapShapes(shape, TopAbs_EDGE, edges);
  TopExp::MapShapes(shape, TopAbs_WIRE, wires);
  for (TopAbs_ShapeEnum type : {TopAbs_VERTEX, TopAbs_EDGE, TopAbs_WIRE, TopAbs_FACE, TopAbs_SHELL, TopAbs_SOLID}) {
    TopTools_IndexedMapOfShape shapes;
    TopExp::MapShapes(shape, type, shapes);
    for (Standard_Integer index = 1; index <= shapes.Extent(); ++index) {
      const TopoDS_Shape& current = shapes(index);
      const BRepCheck_Status status = firstError(analyzer.Result(current), nullptr);
      if (status == BRepCheck_NoError) continue;
      std::string text = std::string(shapeTypeName(type)) + " " + std::to_string(index) + ": " + statusName(status);
      if (type == TopAbs_FACE) {
        for (TopExp_Explorer sub(current, TopAbs_WIRE); sub.More(); sub.Next())
          if (const BRepCheck_Status on = firstError(analyzer.Result(sub.Current()), &current); on != BRepCheck_NoError)
            return text + " (wire " + std::to_string(wires.FindIndex(sub.Current())) + " on it: " + statusName(on) + ")";
        for (TopExp_Explorer sub(current, TopAbs_EDGE); sub.More(); sub.Next())
          if (const BRepCheck_Status on = firstError(analyzer.Result(sub.Current()), &current); on != BRepCheck_NoError)
            return text + " (edge " + std::to_string(edges.FindIndex(sub.Current())) + " on it: " + statusName(on) + ")";
      }
      return text;
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
