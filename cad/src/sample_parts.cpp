// Parts built with OpenCASCADE's modelling API: the fixtures of the tests, benchmarks and docs.
#include "ffdkit/cad/sample_parts.h"

#include <cmath>

#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepOffsetAPI_MakePipe.hxx>
#include <BRepOffsetAPI_MakeThickSolid.hxx>
#include <BRepOffsetAPI_ThruSections.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRep_Tool.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <GC_MakeSegment.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <Geom_Plane.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <gp_Ax2.hxx>
#include <gp_Circ.hxx>

#include "cad_model_data.h"

namespace ffdkit::cad {

namespace {

TopoDS_Shape filletedBox() {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(60.0, 40.0, 30.0).Shape();
  BRepFilletAPI_MakeFillet fillet(box);
  for (TopExp_Explorer it(box, TopAbs_EDGE); it.More(); it.Next()) fillet.Add(5.0, TopoDS::Edge(it.Current()));
  return fillet.Shape();
}

/// A closed, cambered, airfoil-like section: chord `chord` along x, thickness 12% of it, turned by
/// `twist` radians about z and lifted to height z; a periodic cubic interpolating 24 points.
TopoDS_Wire bladeSection(double chord, double twist, double z) {
  const int n = 24;
  Handle(TColgp_HArray1OfPnt) points = new TColgp_HArray1OfPnt(1, n);
  for (int i = 0; i < n; ++i) {
    const double theta = 2.0 * M_PI * i / n;
    const double x = 0.5 * chord * std::cos(theta);
    const double camber = 0.08 * chord * (1.0 - 4.0 * x * x / (chord * chord));
    const double y = 0.06 * chord * std::sin(theta) * (1.2 - x / chord) + camber;
    points->SetValue(i + 1, gp_Pnt(x * std::cos(twist) - y * std::sin(twist), x * std::sin(twist) + y * std::cos(twist), z));
  }
  GeomAPI_Interpolate interpolate(points, true, 1e-9);
  interpolate.Perform();
  return BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(interpolate.Curve()).Edge()).Wire();
}

TopoDS_Shape blade() {
  BRepOffsetAPI_ThruSections loft(true, false, 1e-6);
  const double chords[] = {60.0, 52.0, 44.0, 36.0};
  for (int s = 0; s < 4; ++s) loft.AddWire(bladeSection(chords[s], 0.25 * s, 30.0 * s));
  loft.CheckCompatibility(false);
  loft.Build();
  return loft.Shape();
}

TopoDS_Shape bentPipe() {
  const gp_Pnt a(0, 0, 0), b(0, 0, 40), c(30, 0, 70), d(70, 0, 70);
  const TopoDS_Edge first = BRepBuilderAPI_MakeEdge(a, b).Edge();
  const Handle(Geom_TrimmedCurve) arc = GC_MakeArcOfCircle(gp_Circ(gp_Ax2(gp_Pnt(30, 0, 40), gp_Dir(0, -1, 0)), 30.0), b, c, true).Value();
  const TopoDS_Edge bend = BRepBuilderAPI_MakeEdge(arc).Edge();
  const TopoDS_Edge last = BRepBuilderAPI_MakeEdge(c, d).Edge();
  const TopoDS_Wire spine = BRepBuilderAPI_MakeWire(first, bend, last).Wire();
  const gp_Ax2 axis(a, gp_Dir(0, 0, 1));
  const TopoDS_Wire outer = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(gp_Circ(axis, 8.0)).Edge()).Wire();
  const TopoDS_Wire inner = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(gp_Circ(axis, 6.0)).Edge()).Wire();
  BRepBuilderAPI_MakeFace profile(outer);
  profile.Add(TopoDS::Wire(inner.Reversed()));
  return BRepOffsetAPI_MakePipe(spine, profile.Face()).Shape();
}

/// OCCT's tutorial bottle (MakeBottle(50, 70, 30)) without its thread: profile, prism, fillets,
/// neck, hollowed through the neck's top face.
TopoDS_Shape bottle() {
  const double width = 50.0, height = 70.0, thickness = 30.0;
  const gp_Pnt p1(-width / 2., 0, 0), p2(-width / 2., -thickness / 4., 0), p3(0, -thickness / 2., 0),
      p4(width / 2., -thickness / 4., 0), p5(width / 2., 0, 0);
  const Handle(Geom_TrimmedCurve) arc = GC_MakeArcOfCircle(p2, p3, p4).Value();
  const Handle(Geom_TrimmedCurve) segment1 = GC_MakeSegment(p1, p2).Value();
  const Handle(Geom_TrimmedCurve) segment2 = GC_MakeSegment(p4, p5).Value();
  const TopoDS_Wire half = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(segment1).Edge(), BRepBuilderAPI_MakeEdge(arc).Edge(),
                                                   BRepBuilderAPI_MakeEdge(segment2).Edge())
                               .Wire();
  gp_Trsf mirror;
  mirror.SetMirror(gp::OX());
  const TopoDS_Wire mirrored = TopoDS::Wire(BRepBuilderAPI_Transform(half, mirror).Shape());
  BRepBuilderAPI_MakeWire profile;
  profile.Add(half);
  profile.Add(mirrored);
  const TopoDS_Face face = BRepBuilderAPI_MakeFace(profile.Wire()).Face();
  TopoDS_Shape body = BRepPrimAPI_MakePrism(face, gp_Vec(0, 0, height)).Shape();
  BRepFilletAPI_MakeFillet fillet(body);
  for (TopExp_Explorer it(body, TopAbs_EDGE); it.More(); it.Next()) fillet.Add(thickness / 12., TopoDS::Edge(it.Current()));
  body = fillet.Shape();
  const double neckHeight = height / 10., neckRadius = thickness / 4.;
  const TopoDS_Shape neck = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, height), gp::DZ()), neckRadius, neckHeight).Shape();
  body = BRepAlgoAPI_Fuse(body, neck).Shape();
  TopoDS_Face top;
  double zMax = -1.0;
  for (TopExp_Explorer it(body, TopAbs_FACE); it.More(); it.Next()) {
    const TopoDS_Face& f = TopoDS::Face(it.Current());
    if (auto plane = Handle(Geom_Plane)::DownCast(BRep_Tool::Surface(f))) {
      const double z = plane->Location().Z();
      if (z > zMax) {
        zMax = z;
        top = f;
      }
    }
  }
  TopTools_ListOfShape removed;
  removed.Append(top);
  BRepOffsetAPI_MakeThickSolid hollow;
  hollow.MakeThickSolidByJoin(body, removed, -thickness / 50., 1e-3);
  return hollow.Shape();
}

}  // namespace

std::vector<SamplePart> allSampleParts() {
  return {SamplePart::FilletedBox, SamplePart::Blade, SamplePart::BentPipe, SamplePart::Bottle, SamplePart::TwoPartAssembly};
}

std::string samplePartName(SamplePart part) {
  switch (part) {
    case SamplePart::FilletedBox: return "filleted-box";
    case SamplePart::Blade: return "blade";
    case SamplePart::BentPipe: return "bent-pipe";
    case SamplePart::Bottle: return "bottle";
    case SamplePart::TwoPartAssembly: return "two-part-assembly";
  }
  return "unknown";
}

CadModel makeSamplePart(SamplePart part) {
  CadModel model;
  auto& parts = model.data().parts;
  guardOcct("building the sample part " + samplePartName(part), [&] {
    switch (part) {
      case SamplePart::FilletedBox: parts.push_back({"filleted-box", filletedBox()}); break;
      case SamplePart::Blade: parts.push_back({"blade", blade()}); break;
      case SamplePart::BentPipe: parts.push_back({"bent-pipe", bentPipe()}); break;
      case SamplePart::Bottle: parts.push_back({"bottle", bottle()}); break;
      case SamplePart::TwoPartAssembly: {
        parts.push_back({"plate", BRepPrimAPI_MakeBox(80.0, 50.0, 10.0).Shape()});
        gp_Trsf place;
        place.SetTranslation(gp_Vec(40.0, 25.0, 10.0));
        parts.push_back({"post", BRepPrimAPI_MakeCylinder(10.0, 40.0).Shape().Moved(TopLoc_Location(place))});
        break;
      }
    }
  });
  return model;
}

}  // namespace ffdkit::cad
