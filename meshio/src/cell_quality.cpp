#include "ffdkit/meshio/cell_quality.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include <Eigen/Geometry>

namespace ffdkit::meshio {

namespace {

// OpenFOAM's double-precision constants (OpenFOAM source, doubleScalar.H): SMALL, VSMALL, ROOTVSMALL.
constexpr double kSmall = 1.0e-15;
constexpr double kVerySmall = 1.0e-300;
constexpr double kRootVerySmall = 1.0e-150;

// Points one per row in memory: a face's points are read three times per check, and a
// column-major N x 3 matrix puts each point's coordinates on three cache lines.
using PointRows = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

struct FaceGeometry {
  Eigen::Vector3d centre;
  Eigen::Vector3d area;  ///< area vector: right-hand rule over the face's points, length = area
};

// A face's centre and area vector as OpenFOAM computes them (face::areaAndCentre): a triangle
// directly; a polygon from the triangles between each edge and the point average, the centre
// weighted by the triangles' areas.
FaceGeometry faceGeometry(const PointRows& p, const PolyMeshCells& cells, std::int64_t f) {
  const std::int32_t* v = cells.faceVertices.data() + cells.faceStarts[std::size_t(f)];
  const std::int64_t n = cells.faceStarts[std::size_t(f) + 1] - cells.faceStarts[std::size_t(f)];
  auto point = [&](std::int64_t i) -> Eigen::Vector3d { return p.row(v[i]).transpose(); };
  if (n == 3) {
    const Eigen::Vector3d a = point(0), b = point(1), c = point(2);
    return {(a + b + c) / 3.0, 0.5 * (b - a).cross(c - a)};
  }
  Eigen::Vector3d average = Eigen::Vector3d::Zero();
  for (std::int64_t i = 0; i < n; ++i) average += point(i);
  average /= double(n);
  Eigen::Vector3d sumN = Eigen::Vector3d::Zero(), sumAc = Eigen::Vector3d::Zero();
  double sumA = 0.0;
  for (std::int64_t i = 0; i < n; ++i) {
    const Eigen::Vector3d a = point(i), b = point(i + 1 == n ? 0 : i + 1);
    const Eigen::Vector3d normal = (b - a).cross(average - a);
    const double twiceArea = normal.norm();
    sumN += normal;
    sumA += twiceArea;
    sumAc += twiceArea * (a + b + average);
  }
  if (sumA < kRootVerySmall) return {average, Eigen::Vector3d::Zero()};
  return {sumAc / (3.0 * sumA), 0.5 * sumN};
}

// checkMesh's skewness of a face (OpenFOAM source, primitiveMeshTools.C, faceSkewness and
// boundaryFaceSkewness): the distance of the face centre from where the line between the cell
// centres (or, at the boundary, the face normal through the cell centre) crosses the face,
// over an estimate of the face's extent in that direction.
double faceSkewness(const PointRows& p, const PolyMeshCells& cells, std::int64_t f, const FaceGeometry& face,
                    const Eigen::Vector3d& ownCentre, const Eigen::Vector3d* neiCentre) {
  const Eigen::Vector3d cpf = face.centre - ownCentre;
  Eigen::Vector3d d;
  double spread = 0.2;
  if (neiCentre != nullptr) {
    d = *neiCentre - ownCentre;
  } else {
    const Eigen::Vector3d normal = face.area / (face.area.norm() + kRootVerySmall);
    d = normal * normal.dot(cpf);
    spread = 0.4;
  }
  const Eigen::Vector3d sv = cpf - (face.area.dot(cpf) / (face.area.dot(d) + kRootVerySmall)) * d;
  const Eigen::Vector3d svHat = sv / (sv.norm() + kRootVerySmall);
  double fd = spread * d.norm() + kRootVerySmall;
  for (std::int64_t k = cells.faceStarts[std::size_t(f)]; k < cells.faceStarts[std::size_t(f) + 1]; ++k)
    fd = std::max(fd, std::abs(svHat.dot(p.row(cells.faceVertices[std::size_t(k)]).transpose() - face.centre)));
  return sv.norm() / fd;
}

}  // namespace

namespace {

// Faces are visited in chunks: the geometry of a chunk's faces (and, in the last pass, their
// checks) is computed in parallel into a small buffer, then used in face order, so that every sum
// adds in the same order whatever the number of threads.
constexpr std::int64_t kFaceChunk = std::int64_t(1) << 14;

template <class Compute, class Use>
void forFaceChunks(std::int64_t faces, Compute&& compute, Use&& use) {
  for (std::int64_t begin = 0; begin < faces; begin += kFaceChunk) {
    const std::int64_t end = std::min(faces, begin + kFaceChunk);
#pragma omp parallel for schedule(static) if (end - begin > 1024)
    for (std::int64_t f = begin; f < end; ++f) compute(f, f - begin);
    for (std::int64_t f = begin; f < end; ++f) use(f, f - begin);
  }
}

// What the last pass finds at one face.
struct FaceCheck {
  double ownPyramid = 0.0;
  double neiPyramid = 0.0;  ///< internal faces
  double cosine = 1.0;      ///< internal faces: between the centres' line and the area vector
  double skewness = 0.0;
};

}  // namespace

CellQuality checkPolyMeshCells(const Eigen::MatrixX3d& columns, const PolyMeshCells& cells,
                               const CellQualityOptions& options) {
  const PointRows points = columns;
  CellQuality q;
  const std::int64_t faces = cells.faceCount();
  const std::int64_t internal = std::int64_t(cells.neighbour.size());
  q.cellCount = cells.cellCount;
  q.faceCount = faces;
  const std::size_t nCells = std::size_t(cells.cellCount);
  std::vector<FaceGeometry> geometry(std::size_t(std::min(faces, kFaceChunk)));
  auto computeGeometry = [&](std::int64_t f, std::int64_t k) { geometry[std::size_t(k)] = faceGeometry(points, cells, f); };

  // First estimate of each cell centre: the average of its face centres.
  PointRows estimate = PointRows::Zero(Eigen::Index(nCells), 3);
  std::vector<std::int32_t> faceCounts(nCells, 0);
  forFaceChunks(faces, computeGeometry, [&](std::int64_t f, std::int64_t k) {
    const Eigen::Vector3d& c = geometry[std::size_t(k)].centre;
    const std::size_t own = std::size_t(cells.owner[std::size_t(f)]);
    estimate.row(Eigen::Index(own)) += c.transpose();
    ++faceCounts[own];
    if (f < internal) {
      const std::size_t nei = std::size_t(cells.neighbour[std::size_t(f)]);
      estimate.row(Eigen::Index(nei)) += c.transpose();
      ++faceCounts[nei];
    }
  });
  for (std::size_t c = 0; c < nCells; ++c) estimate.row(Eigen::Index(c)) /= double(std::max(1, faceCounts[c]));
  faceCounts = {};

  // Volumes and centres from the face pyramids about the estimate (3 x volume accumulated).
  PointRows centres = PointRows::Zero(Eigen::Index(nCells), 3);
  Eigen::VectorXd volumes = Eigen::VectorXd::Zero(Eigen::Index(nCells));
  auto addPyramid = [&](std::size_t cell, const FaceGeometry& face, double sign) {
    const Eigen::Vector3d apex = estimate.row(Eigen::Index(cell)).transpose();
    const double volume3 = sign * face.area.dot(face.centre - apex);
    centres.row(Eigen::Index(cell)) += volume3 * (0.75 * face.centre + 0.25 * apex).transpose();
    volumes[Eigen::Index(cell)] += volume3;
  };
  forFaceChunks(faces, computeGeometry, [&](std::int64_t f, std::int64_t k) {
    const FaceGeometry& face = geometry[std::size_t(k)];
    addPyramid(std::size_t(cells.owner[std::size_t(f)]), face, 1.0);
    if (f < internal) addPyramid(std::size_t(cells.neighbour[std::size_t(f)]), face, -1.0);
  });
  for (std::size_t c = 0; c < nCells; ++c) {
    const Eigen::Index i = Eigen::Index(c);
    if (std::abs(volumes[i]) > kVerySmall) centres.row(i) /= volumes[i];
    else centres.row(i) = estimate.row(i);
  }
  volumes /= 3.0;
  estimate = PointRows();
  geometry = {};

  std::vector<char> bad(nCells, 0);
  q.minVolume = std::numeric_limits<double>::infinity();
  q.maxVolume = -std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < nCells; ++c) {
    const double v = volumes[Eigen::Index(c)];
    if (v < kVerySmall) {
      ++q.negativeVolumeCells;
      bad[c] = 1;
    }
    q.minVolume = std::min(q.minVolume, v);
    q.maxVolume = std::max(q.maxVolume, v);
    q.totalVolume += v;
  }

  // Each face's pyramids about the two cell centres, its non-orthogonality and skewness.
  q.minPyramidVolume = std::numeric_limits<double>::infinity();
  double sumCosines = 0.0;
  double minCosine = 1.0;
  std::vector<FaceCheck> checks(std::size_t(std::min(faces, kFaceChunk)));
  auto computeCheck = [&](std::int64_t f, std::int64_t k) {
    const FaceGeometry face = faceGeometry(points, cells, f);
    FaceCheck& r = checks[std::size_t(k)];
    const Eigen::Vector3d ownCentre = centres.row(Eigen::Index(cells.owner[std::size_t(f)])).transpose();
    r.ownPyramid = face.area.dot(face.centre - ownCentre) / 3.0;
    if (f < internal) {
      const Eigen::Vector3d neiCentre = centres.row(Eigen::Index(cells.neighbour[std::size_t(f)])).transpose();
      r.neiPyramid = face.area.dot(neiCentre - face.centre) / 3.0;
      const Eigen::Vector3d d = neiCentre - ownCentre;
      r.cosine = d.dot(face.area) / (d.norm() * face.area.norm() + kRootVerySmall);
      r.skewness = faceSkewness(points, cells, f, face, ownCentre, &neiCentre);
    } else {
      r.skewness = faceSkewness(points, cells, f, face, ownCentre, nullptr);
    }
  };
  forFaceChunks(faces, computeCheck, [&](std::int64_t f, std::int64_t k) {
    const FaceCheck& r = checks[std::size_t(k)];
    q.minPyramidVolume = std::min(q.minPyramidVolume, r.ownPyramid);
    if (r.ownPyramid < -kSmall) {
      ++q.incorrectlyOrientedFaces;
      bad[std::size_t(cells.owner[std::size_t(f)])] = 1;
    }
    if (f < internal) {
      q.minPyramidVolume = std::min(q.minPyramidVolume, r.neiPyramid);
      if (r.neiPyramid < -kSmall) {
        ++q.incorrectlyOrientedFaces;
        bad[std::size_t(cells.neighbour[std::size_t(f)])] = 1;
      }
      minCosine = std::min(minCosine, r.cosine);
      sumCosines += r.cosine;
    }
    q.maxSkewness = std::max(q.maxSkewness, r.skewness);
  });
  // The largest angle is the smallest cosine's (acos decreases): one acos, not one per face.
  if (internal > 0) q.maxNonOrthogonality = std::acos(std::clamp(minCosine, -1.0, 1.0)) * 180.0 / std::numbers::pi;
  // checkMesh's average: the angle of the mean cosine (not the mean angle).
  if (internal > 0)
    q.meanNonOrthogonality = std::acos(std::clamp(sumCosines / double(internal), -1.0, 1.0)) * 180.0 / std::numbers::pi;
  if (faces == 0) q.minPyramidVolume = 0.0;
  if (nCells == 0) q.minVolume = q.maxVolume = 0.0;
  for (std::size_t c = 0; c < nCells; ++c)
    if (bad[c] != 0) {
      ++q.badCells;
      if (q.firstBadCells.size() < options.listedIds) q.firstBadCells.push_back(std::int64_t(c));
    }
  return q;
}

std::string cellQualityText(const CellQuality& q) {
  char line[512];
  std::snprintf(line, sizeof line,
                "%lld cells: volume min %.6g max %.6g (min/max %.6g), worst face pyramid %.6g, "
                "non-orthogonality max %.6g mean %.6g deg, skewness max %.6g",
                static_cast<long long>(q.cellCount), q.minVolume, q.maxVolume, q.volumeRatio(), q.minPyramidVolume,
                q.maxNonOrthogonality, q.meanNonOrthogonality, q.maxSkewness);
  return line;
}

std::string badCellsText(const CellQuality& q) {
  std::string ids;
  for (std::int64_t id : q.firstBadCells) ids.append(ids.empty() ? "" : ", ").append(std::to_string(id));
  if (q.badCells > std::int64_t(q.firstBadCells.size())) ids.append(", ...");
  return std::to_string(q.badCells) + " of " + std::to_string(q.cellCount) + " cells inverted or of zero volume (first: " +
         ids + "); as checkMesh counts them: " + std::to_string(q.negativeVolumeCells) + " negative-volume cells, " +
         std::to_string(q.incorrectlyOrientedFaces) + " incorrectly oriented faces";
}

}  // namespace ffdkit::meshio
