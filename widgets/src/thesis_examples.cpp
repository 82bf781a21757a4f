#include "ffdkit/widgets/thesis_examples.h"

#include <cmath>
#include <numbers>

namespace ffdkit::widgets {
namespace {

using std::numbers::pi;

// A placement that turns the widget's local x onto the unit `direction` (given in the cell's
// axes); built from cross products so that axis directions give exact matrices.
Eigen::Affine3d pointing(const Eigen::Vector3d& direction) {
  const Eigen::Vector3d x = direction.normalized();
  const Eigen::Vector3d up = std::abs(x.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  a.linear().col(0) = x;
  a.linear().col(1) = up.cross(x).normalized();
  a.linear().col(2) = x.cross(a.linear().col(1));
  return a;
}

AffineOptions named(std::string name, const Eigen::Affine3d& placement = Eigen::Affine3d::Identity()) {
  AffineOptions o;
  o.name = std::move(name);
  o.placement = placement;
  return o;
}

}  // namespace

Fig62 buildFig62() {
  Fig62 f;
  WidgetModel& m = f.model;
  f.lattice = m.addLattice("unit-box", Eigen::Vector3i(3, 3, 3));
  f.face = m.addCell(f.lattice, CellSpec::face(0, 0, 2, 2), "red-face");
  f.edge = m.addCell(f.lattice, CellSpec::edge(0, 2, 0, 0), "green-edge");
  f.point = m.addCell(f.lattice, CellSpec::point(2, 2, 0), "blue-point");
  f.faceRotate = m.addAffine(f.face, AffineKind::Rotate, named("red-ring"));
  f.edgeTranslate = m.addAffine(f.edge, AffineKind::Translate, named("green-arrow"));
  f.pointTranslate = m.addAffine(f.point, AffineKind::Translate, named("blue-arrow", pointing(Eigen::Vector3d::UnitZ())));
  return f;
}

Fig68 buildFig68() {
  Fig68 f;
  WidgetModel& m = f.model;
  f.lattice = m.addLattice("lattice", Eigen::Vector3i(2, 3, 2));
  // Faces with normal y have axes x = lattice z, z = lattice y (Kuriyama 1996, sec. 6.2.1); edges
  // along x keep the lattice axes. Directions below are in those cell axes.
  f.faceA = m.addCell(f.lattice, CellSpec::face(0, 0, 0, 1), "face-front");
  f.faceB = m.addCell(f.lattice, CellSpec::face(0, 2, 0, 1), "face-back");
  f.edgeA = m.addCell(f.lattice, CellSpec::edge(0, 0, 1, 0), "edge-front");
  f.edgeB = m.addCell(f.lattice, CellSpec::edge(0, 2, 1, 0), "edge-back");
  f.faceTranslateA = m.addAffine(f.faceA, AffineKind::Translate, named("push-front", pointing(-Eigen::Vector3d::UnitZ())));
  f.faceTranslateB = m.addAffine(f.faceB, AffineKind::Translate, named("push-back", pointing(Eigen::Vector3d::UnitZ())));
  f.faceRotateA = m.addAffine(f.faceA, AffineKind::Rotate, named("turn-front"));
  f.faceRotateB = m.addAffine(f.faceB, AffineKind::Rotate, named("turn-back"));
  f.edgeTranslateA = m.addAffine(f.edgeA, AffineKind::Translate, named("pull-front", pointing(-Eigen::Vector3d::UnitY())));
  f.edgeTranslateB = m.addAffine(f.edgeB, AffineKind::Translate, named("pull-back", pointing(Eigen::Vector3d::UnitY())));
  m.bind(f.faceTranslateA, f.faceTranslateB);
  m.bind(f.faceRotateA, f.faceRotateB);
  m.bind(f.edgeTranslateA, f.edgeTranslateB);
  return f;
}

Fig69 buildFig69() {
  Fig69 f;
  WidgetModel& m = f.model;
  f.parent = m.addLattice("parent", Eigen::Vector3i(2, 2, 2));
  // The child straddles the parent's top face (z from 0.75 to 1.25): an object reaching the
  // face passes through both lattices, so the child's widgets deform it too.
  Eigen::Affine3d childFrame = Eigen::Affine3d::Identity();
  childFrame.translate(Eigen::Vector3d(0.25, 0.25, 0.75)).scale(0.5);
  LatticeOptions child;
  child.name = "child";
  child.frame = childFrame;
  f.child = m.addLattice(child);
  f.topFace = m.addCell(f.parent, CellSpec::face(0, 0, 1, 2), "top");
  m.bind(f.topFace, f.child);
  f.faceLift = m.addAffine(f.topFace, AffineKind::Translate, named("lift", pointing(Eigen::Vector3d::UnitZ())));
  const WidgetId p0 = m.addCell(f.parent, CellSpec::point(0, 0, 0), "corner-left");
  const WidgetId p1 = m.addCell(f.parent, CellSpec::point(1, 0, 0), "corner-right");
  f.pointA = m.addAffine(p0, AffineKind::Translate, named("spread-left", pointing(-Eigen::Vector3d::UnitX())));
  f.pointB = m.addAffine(p1, AffineKind::Translate, named("spread-right"));
  m.bind(f.pointA, f.pointB);
  const WidgetId e0 = m.addCell(f.parent, CellSpec::edge(0, 1, 0, 0), "parent-edge");
  const WidgetId e1 = m.addCell(f.child, CellSpec::edge(0, 0, 0, 0), "child-edge");
  f.parentEdge = m.addAffine(e0, AffineKind::Translate, named("parent-push", pointing(Eigen::Vector3d::UnitY())));
  f.childEdge = m.addAffine(e1, AffineKind::Translate, named("child-push", pointing(Eigen::Vector3d::UnitY())));
  m.bind(f.parentEdge, f.childEdge);
  return f;
}

Fig610 buildFig610(double pitch, std::optional<VariationRange> clamp) {
  Fig610 f;
  WidgetModel& m = f.model;
  f.lattice = m.addLattice("press-frame", Eigen::Vector3i(2, 2, 2));
  f.topFace = m.addCell(f.lattice, CellSpec::face(0, 0, 1, 2), "jaw");
  f.press = m.addAffine(f.topFace, AffineKind::Translate, named("press", pointing(-Eigen::Vector3d::UnitZ())));
  Eigen::Affine3d handleFrame = Eigen::Affine3d::Identity();
  handleFrame.translation() = Eigen::Vector3d(0.5, 0.5, 1.5);
  AffineOptions handle = named("handle", handleFrame);
  // The parts library's crank (app/parts), scaled so that its knob stands on the circle of radius
  // one glyph size about z where WidgetModel::pick finds a rotate widget: the user grabs the knob.
  handle.glyph = Glyph{"crank", 0.3, Eigen::Affine3d(Eigen::Scaling(2.2, 2.2, 1.2))};
  f.handle = m.addFreeAffine(AffineKind::Rotate, handle);
  ConversionRule rule = ConversionRule::screw(pitch);
  rule.clamp = clamp;
  f.screw = m.bind(f.handle, f.press, rule);
  return f;
}

}  // namespace ffdkit::widgets
