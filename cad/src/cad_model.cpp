#include "ffdkit/cad/cad_model.h"

#include <Bnd_Box.hxx>
#include <BRepBndLib.hxx>
#include <TopAbs_ShapeEnum.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>

#include "cad_model_data.h"

namespace ffdkit::cad {

std::string describeFailure(const std::string& what, const Standard_Failure& failure) {
  const char* message = failure.GetMessageString();
  std::string text = what + ": OpenCASCADE " + failure.DynamicType()->Name();
  if (message != nullptr && *message != '\0') text += " (" + std::string(message) + ")";
  return text;
}

CadModel::CadModel() : data_(std::make_shared<CadModelData>()) {}

int CadModel::partCount() const { return static_cast<int>(data_->parts.size()); }

const std::string& CadModel::partName(int part) const {
  if (part < 0 || part >= partCount())
    throw CadError("part " + std::to_string(part) + " is out of range (the model has " + std::to_string(partCount()) + ")");
  return data_->parts[part].name;
}

Eigen::AlignedBox3d CadModel::bounds() const {
  Eigen::AlignedBox3d box;
  for (const auto& part : data_->parts) {
    Bnd_Box b;
    guardOcct("bounding box of part '" + part.name + "'", [&] { BRepBndLib::Add(part.shape, b, false); });
    if (b.IsVoid()) continue;
    double x0, y0, z0, x1, y1, z1;
    b.Get(x0, y0, z0, x1, y1, z1);
    box.extend(Eigen::Vector3d(x0, y0, z0));
    box.extend(Eigen::Vector3d(x1, y1, z1));
  }
  return box;
}

CadModel::Counts CadModel::counts() const {
  Counts counts;
  auto count = [](const TopoDS_Shape& shape, TopAbs_ShapeEnum type) {
    TopTools_IndexedMapOfShape map;
    TopExp::MapShapes(shape, type, map);
    return map.Extent();
  };
  for (const auto& part : data_->parts) {
    counts.solids += count(part.shape, TopAbs_SOLID);
    counts.shells += count(part.shape, TopAbs_SHELL);
    counts.faces += count(part.shape, TopAbs_FACE);
    counts.edges += count(part.shape, TopAbs_EDGE);
    counts.vertices += count(part.shape, TopAbs_VERTEX);
  }
  return counts;
}

}  // namespace ffdkit::cad
