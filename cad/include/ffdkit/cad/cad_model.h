#pragma once

#include <memory>
#include <string>

#include <Eigen/Geometry>

namespace ffdkit::cad {

struct CadModelData;  // OpenCASCADE shapes, defined in the module's sources only

/// A CAD model: named parts, each a boundary representation (solid, shell or faces) placed in the
/// world, as read from STEP or IGES (an assembly's parts flattened, each with its placement and
/// name). Value type sharing its shapes: a copy is cheap and deformations make new shapes.
/// OpenCASCADE stays out of this header (the shapes live behind CadModelData).
class CadModel {
 public:
  /// An empty model (no parts).
  CadModel();

  /// Number of parts.
  int partCount() const;
  /// Name of part `part` (from the file's product or label names; "part-N" when it has none).
  /// @throws CadError if part is out of range.
  const std::string& partName(int part) const;
  /// The union of the parts' bounding boxes in the world (empty box for an empty model).
  Eigen::AlignedBox3d bounds() const;

  /// Topology counts over all parts (shared sub-shapes counted once per part).
  struct Counts {
    int solids = 0;    ///< closed volumes
    int shells = 0;    ///< connected face sets
    int faces = 0;     ///< trimmed surfaces
    int edges = 0;     ///< curves bounding faces
    int vertices = 0;  ///< points bounding edges
  };
  /// Counts of solids, shells, faces, edges and vertices.
  Counts counts() const;

  /// The shapes (for the module's own sources; CadModelData is not defined in public headers).
  const CadModelData& data() const { return *data_; }
  /// Mutable shapes (the module's sources build models through it).
  CadModelData& data() { return *data_; }

 private:
  std::shared_ptr<CadModelData> data_;
};

}  // namespace ffdkit::cad
