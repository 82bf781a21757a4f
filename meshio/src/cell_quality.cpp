#include "ffdkit/meshio/cell_quality.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <numbers>

#include <Eigen/Geometry>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace ffdkit::meshio {

namespace detail {
void quadGeometryLanes(const double* x, const double* y, const double* z, int stride, int count, double* cx, double* cy,
                       double* cz, double* ax, double* ay, double* az);

// Faces to check, one per lane: each face's centre and area vector and its two cells' centres in;
// its two pyramids, the cosine of its non-orthogonality and what its skewness needs besides its
// points out (faceCheckLanes).
struct FaceCheckLanes {
  static constexpr int kLanes = 64;  // a few KiB per array: the lanes stay in the L1 cache while they fill
  double fcx[kLanes], fcy[kLanes], fcz[kLanes];  // the face's centre
  double fax[kLanes], fay[kLanes], faz[kLanes];  // its area vector
  double ocx[kLanes], ocy[kLanes], ocz[kLanes];  // its owner's centre
  double ncx[kLanes], ncy[kLanes], ncz[kLanes];  // its neighbour's centre (a boundary face: the owner's)
  double ownPyramid[kLanes], neiPyramid[kLanes], cosine[kLanes];
  // An internal face's skewness is svNorm / max(spread, |svHat . (point - centre)| over its points),
  // at most skewnessBound = svNorm / spread.
  double hx[kLanes], hy[kLanes], hz[kLanes];  // svHat
  double svNorm[kLanes], spread[kLanes], skewnessBound[kLanes];
  std::int64_t face[kLanes];
  bool quadInside[kLanes];  // an internal quadrilateral: the fields above give its skewness
  int count = 0;
};
void faceCheckLanes(FaceCheckLanes& lanes);
}  // namespace detail

namespace {

// OpenFOAM's double-precision constants (OpenFOAM source, doubleScalar.H): SMALL, VSMALL, ROOTVSMALL.
constexpr double kSmall = 1.0e-15;
constexpr double kVerySmall = 1.0e-300;
constexpr double kRootVerySmall = 1.0e-150;

// The points as they are given (#P x 3, column-major), read in place: a copy one per row would
// cost 24 bytes per point for little gain, since neighbouring faces share their points' lines.
struct PointColumns {
  explicit PointColumns(const Eigen::MatrixX3d& points)
      : x(points.col(0).data()), y(points.col(1).data()), z(points.col(2).data()) {}
  Eigen::Vector3d operator[](std::int32_t i) const { return {x[i], y[i], z[i]}; }
  const double* x;
  const double* y;
  const double* z;
};

// A label list as the check reads it: loads that take any alignment (a list read in place from a
// mapped file starts at any byte offset of it, LabelList).
struct Labels {
  explicit Labels(const char* at) : bytes(at) {}
  std::int32_t operator[](std::int64_t i) const {
    std::int32_t label;
    std::memcpy(&label, bytes + i * std::int64_t(sizeof label), sizeof label);
    return label;
  }
  Labels operator+(std::int64_t i) const { return Labels(bytes + i * std::int64_t(sizeof(std::int32_t))); }
  const char* bytes;
};

// The mesh's lists (PolyMeshCells) as the check reads them.
struct MeshLabels {
  explicit MeshLabels(const PolyMeshCells& cells)
      : starts(cells.faceStarts.bytes()), vertices(cells.faceVertices.bytes()), owner(cells.owner.bytes()),
        neighbour(cells.neighbour.bytes()) {}
  Labels pointsOf(std::int64_t f) const { return vertices + starts[f]; }  // face f's point indices
  std::int64_t sizeOf(std::int64_t f) const { return std::int64_t(starts[f + 1]) - starts[f]; }  // its number of points
  Labels starts, vertices, owner, neighbour;
};

struct FaceGeometry {
  Eigen::Vector3d centre;
  Eigen::Vector3d area;  ///< area vector: right-hand rule over the face's points, length = area
};

// A face's centre and area vector as OpenFOAM computes them (face::areaAndCentre): a triangle
// directly; a polygon from the triangles between each edge and the point average, the centre
// weighted by the triangles' areas.
FaceGeometry faceGeometry(const PointColumns& p, const MeshLabels& m, std::int64_t f) {
  const Labels v = m.pointsOf(f);
  const std::int64_t n = m.sizeOf(f);
  auto point = [&](std::int64_t i) -> Eigen::Vector3d { return p[v[i]]; };
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

// Faces' geometry many at a time, one face per lane: quadrilaterals (a hexahedral mesh's faces)
// by the kernel below, the others one by one by faceGeometry. Each lane's result is bit for bit
// faceGeometry's.
struct FaceLanes {
  static constexpr int kLanes = 256;
  // Inputs of the quadrilateral kernel: the 4 points of the face in each lane.
  double x[4][kLanes], y[4][kLanes], z[4][kLanes];
  // Results: centre and area vector of the face in each lane.
  double cx[kLanes], cy[kLanes], cz[kLanes], ax[kLanes], ay[kLanes], az[kLanes];
  int count = 0;
  // Lanes of faces that are not quadrilaterals, with their geometry.
  std::vector<std::pair<int, FaceGeometry>> others;

  void clear() {
    count = 0;
    others.clear();
  }
  // Puts face f in the next lane.
  void add(const PointColumns& p, const MeshLabels& m, std::int64_t f) {
    const int lane = count++;
    if (m.sizeOf(f) == 4) {
      const Labels v = m.pointsOf(f);
      for (int k = 0; k < 4; ++k) {
        x[k][lane] = p.x[v[k]];
        y[k][lane] = p.y[v[k]];
        z[k][lane] = p.z[v[k]];
      }
    } else {
      for (int k = 0; k < 4; ++k) x[k][lane] = y[k][lane] = z[k][lane] = 0.0;
      others.emplace_back(lane, faceGeometry(p, m, f));
    }
  }
  // Computes every lane's geometry.
  void compute() {
    detail::quadGeometryLanes(x[0], y[0], z[0], kLanes, count, cx, cy, cz, ax, ay, az);
    for (const auto& [lane, g] : others) {
      cx[lane] = g.centre.x(), cy[lane] = g.centre.y(), cz[lane] = g.centre.z();
      ax[lane] = g.area.x(), ay[lane] = g.area.y(), az[lane] = g.area.z();
    }
  }
  FaceGeometry operator[](int lane) const {
    return {{cx[lane], cy[lane], cz[lane]}, {ax[lane], ay[lane], az[lane]}};
  }
};

// Puts face f, of geometry `g`, in the next lane of `lanes` (which has room) with its owner's
// centre and, for an internal face, its neighbour's (3 doubles each).
void addFaceCheck(detail::FaceCheckLanes& lanes, const MeshLabels& m, std::int64_t f, const FaceGeometry& g,
                  const double* own, const double* nei) {
  const int l = lanes.count++;
  lanes.face[l] = f;
  lanes.fcx[l] = g.centre.x(), lanes.fcy[l] = g.centre.y(), lanes.fcz[l] = g.centre.z();
  lanes.fax[l] = g.area.x(), lanes.fay[l] = g.area.y(), lanes.faz[l] = g.area.z();
  lanes.ocx[l] = own[0], lanes.ocy[l] = own[1], lanes.ocz[l] = own[2];
  if (nei == nullptr) nei = own;
  lanes.ncx[l] = nei[0], lanes.ncy[l] = nei[1], lanes.ncz[l] = nei[2];
  lanes.quadInside[l] = nei != own && m.sizeOf(f) == 4;
}

// The skewness of the internal quadrilateral f in lane l, from the kernel's part and the face's
// points: the last step of faceSkewness, in its operations and order.
double quadSkewness(const detail::FaceCheckLanes& L, int l, const PointColumns& p, const MeshLabels& m,
                    std::int64_t f) {
  const Labels v = m.pointsOf(f);
  double fd = L.spread[l];
  for (int k = 0; k < 4; ++k) {
    const std::int32_t i = v[k];
    const double qx = p.x[i] - L.fcx[l], qy = p.y[i] - L.fcy[l], qz = p.z[i] - L.fcz[l];
    fd = std::max(fd, std::abs(L.hx[l] * qx + L.hy[l] * qy + L.hz[l] * qz));
  }
  return L.svNorm[l] / fd;
}

// checkMesh's skewness of a face (OpenFOAM source, primitiveMeshTools.C, faceSkewness and
// boundaryFaceSkewness): the distance of the face centre from where the line between the cell
// centres (or, at the boundary, the face normal through the cell centre) crosses the face,
// over an estimate of the face's extent in that direction.
double faceSkewness(const PointColumns& p, const MeshLabels& m, std::int64_t f, const FaceGeometry& face,
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
  const Labels v = m.pointsOf(f);
  for (std::int64_t k = 0, n = m.sizeOf(f); k < n; ++k) fd = std::max(fd, std::abs(svHat.dot(p[v[k]] - face.centre)));
  return sv.norm() / fd;
}

}  // namespace

namespace detail {

// faceGeometry of `count` quadrilaterals, one per lane: point k of lane l at x[k * stride + l]
// (and y, z). The same operations in the same order as faceGeometry's Eigen expressions for
// n == 4, so that each result is bit for bit faceGeometry's; written for the compiler to
// vectorise across lanes (SSE2, or AVX2 where the processor has it: AVX2 brings no fused
// multiply-add, which would round differently).
// The file is compiled with -fno-math-errno and -fno-trapping-math (meshio/CMakeLists.txt): the
// square roots are of sums of squares, the results are the same, and without them errno's branch
// and the division's possible trap keep the loop from being vectorised.
__attribute__((target_clones("avx2", "default"))) void quadGeometryLanes(
    const double* __restrict x, const double* __restrict y, const double* __restrict z, int stride, int count,
    double* __restrict cx, double* __restrict cy, double* __restrict cz, double* __restrict ax, double* __restrict ay,
    double* __restrict az) {
  for (int l = 0; l < count; ++l) {
    double mx = 0.0, my = 0.0, mz = 0.0;
#pragma GCC unroll 4
    for (int k = 0; k < 4; ++k) {
      mx += x[k * stride + l];
      my += y[k * stride + l];
      mz += z[k * stride + l];
    }
    mx /= 4.0;
    my /= 4.0;
    mz /= 4.0;
    double nX = 0.0, nY = 0.0, nZ = 0.0, sumA = 0.0, sX = 0.0, sY = 0.0, sZ = 0.0;
#pragma GCC unroll 4
    for (int k = 0; k < 4; ++k) {
      const int j = (k + 1) & 3;
      const double px = x[k * stride + l], py = y[k * stride + l], pz = z[k * stride + l];
      const double qx = x[j * stride + l], qy = y[j * stride + l], qz = z[j * stride + l];
      const double ex = qx - px, ey = qy - py, ez = qz - pz;  // b - a
      const double fx = mx - px, fy = my - py, fz = mz - pz;  // average - a
      const double nx = ey * fz - ez * fy, ny = ez * fx - ex * fz, nz = ex * fy - ey * fx;
      const double twiceArea = std::sqrt(nx * nx + ny * ny + nz * nz);
      nX += nx;
      nY += ny;
      nZ += nz;
      sumA += twiceArea;
      sX += twiceArea * (px + qx + mx);
      sY += twiceArea * (py + qy + my);
      sZ += twiceArea * (pz + qz + mz);
    }
    // Both results computed, one kept: a branch would keep the loop from being vectorised.
    const bool flat = sumA < kRootVerySmall;
    const double sumA3 = 3.0 * sumA;
    const double qx = sX / sumA3, qy = sY / sumA3, qz = sZ / sumA3;
    const double hx = 0.5 * nX, hy = 0.5 * nY, hz = 0.5 * nZ;
    cx[l] = flat ? mx : qx;
    cy[l] = flat ? my : qy;
    cz[l] = flat ? mz : qz;
    ax[l] = flat ? 0.0 : hx;
    ay[l] = flat ? 0.0 : hy;
    az[l] = flat ? 0.0 : hz;
  }
}

// checkMesh's face checks of `lanes.count` faces, one face per lane: the pyramids and the cosine
// as OpenFOAM computes them (primitiveMeshCheck.C), and of an internal face's skewness all that
// faceSkewness computes before it reads the face's points (svHat, |sv|, the spread term) and the
// bound that those give, in the same operations and order as the Eigen expressions they were
// written with before (a dot product and a squared norm add their terms from the first): each
// lane's results are bit for bit those, and quadSkewness ends the skewness as faceSkewness does.
// A boundary face's cosine and skewness terms, and those of a face that is not a quadrilateral,
// are computed but not used (faceSkewness gives them). Compiled as quadGeometryLanes is, for the
// compiler to vectorise across lanes.
__attribute__((target_clones("avx2", "default"))) void faceCheckLanes(FaceCheckLanes& lanes) {
  FaceCheckLanes& __restrict L = lanes;
  const int count = L.count;
  for (int l = 0; l < count; ++l) {
    const double fcx = L.fcx[l], fcy = L.fcy[l], fcz = L.fcz[l];
    const double fax = L.fax[l], fay = L.fay[l], faz = L.faz[l];
    const double ocx = L.ocx[l], ocy = L.ocy[l], ocz = L.ocz[l];
    const double ncx = L.ncx[l], ncy = L.ncy[l], ncz = L.ncz[l];
    const double cx = fcx - ocx, cy = fcy - ocy, cz = fcz - ocz;  // face centre - owner's centre (cpf)
    const double areaDotC = fax * cx + fay * cy + faz * cz;
    L.ownPyramid[l] = areaDotC / 3.0;
    const double nx = ncx - fcx, ny = ncy - fcy, nz = ncz - fcz;
    L.neiPyramid[l] = (fax * nx + fay * ny + faz * nz) / 3.0;
    const double dx = ncx - ocx, dy = ncy - ocy, dz = ncz - ocz;
    const double dNorm = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double areaNorm = std::sqrt(fax * fax + fay * fay + faz * faz);
    L.cosine[l] = (dx * fax + dy * fay + dz * faz) / (dNorm * areaNorm + kRootVerySmall);
    // faceSkewness of an internal face.
    const double t = areaDotC / (fax * dx + fay * dy + faz * dz + kRootVerySmall);
    const double sx = cx - t * dx, sy = cy - t * dy, sz = cz - t * dz;
    const double svNorm = std::sqrt(sx * sx + sy * sy + sz * sz);
    const double svScale = svNorm + kRootVerySmall;
    L.hx[l] = sx / svScale, L.hy[l] = sy / svScale, L.hz[l] = sz / svScale;
    const double spread = 0.2 * dNorm + kRootVerySmall;
    L.svNorm[l] = svNorm;
    L.spread[l] = spread;
    // max() of the spread and more is at least the spread, and a division by a larger positive
    // number rounds to no more: the skewness is at most this.
    L.skewnessBound[l] = svNorm / spread;
  }
}

}  // namespace detail


namespace {

// Cells and faces are visited in blocks of this many, in parallel; each block's share of a sum,
// minimum or count is kept apart and the shares are combined in block order, so that every
// result is the same whatever the number of threads.
constexpr int kBlockBits = 13;
constexpr std::int64_t kBlock = std::int64_t(1) << kBlockBits;

// The faces of each cell, in increasing face order: faces[starts[c] .. starts[c + 1]), each a
// face index with kNeighbourSide set when the cell is the face's neighbour. 4 bytes per cell and
// per (cell, face) pair: an owner list has at most INT32_MAX faces and a neighbour list fewer, so
// the pairs number below 2^32.
// Both arrays are left unwritten when allocated: the threads that fill them write each page
// first, on both cores, with no zero fill before.
struct CellFaces {
  static constexpr std::uint32_t kNeighbourSide = std::uint32_t(1) << 31;
  std::unique_ptr<std::uint32_t[]> starts;  // #cells + 1
  std::unique_ptr<std::uint32_t[]> faces;   // #faces + #internal faces
};

// `count` items, not written (no zero fill: the memory is first written by the threads that fill it).
template <class T>
std::unique_ptr<T[]> unwrittenArray(std::size_t count) {
  return std::make_unique_for_overwrite<T[]>(count);
}

// Calls visit(c - first, entry) for each (cell, face) pair of the cells [first, first + span), in
// face order: the internal faces [from, to) (entry f, or f | kNeighbourSide on the neighbour's
// side), then every boundary face. The one walk behind both ways of making the lists (the whole
// mesh's, the sweep's), once to count each cell's faces and once to list them.
template <class Visit>
void forEachFaceOfCells(const Labels& owner, const Labels& neighbour, std::int64_t internal, std::int64_t faces,
                        std::int64_t from, std::int64_t to, std::int64_t first, std::uint32_t span, Visit&& visit) {
  for (std::int64_t f = from; f < to; ++f) {
    if (std::uint32_t(owner[f] - first) < span) visit(owner[f] - first, std::uint32_t(f));
    if (std::uint32_t(neighbour[f] - first) < span)
      visit(neighbour[f] - first, std::uint32_t(f) | CellFaces::kNeighbourSide);
  }
  for (std::int64_t f = internal; f < faces; ++f)
    if (std::uint32_t(owner[f] - first) < span) visit(owner[f] - first, std::uint32_t(f));
}

// Built in parallel: each thread takes a range of cells and walks every face for those of its
// range, so that each cell's faces come in face order without a sort.
CellFaces cellFacesOf(const PolyMeshCells& cells) {
  const std::int64_t nCells = cells.cellCount;
  const std::int64_t faces = cells.faceCount();
  const std::int64_t internal = std::int64_t(cells.neighbour.size());
  const Labels owner(cells.owner.bytes()), neighbour(cells.neighbour.bytes());
  CellFaces r;
  r.faces = unwrittenArray<std::uint32_t>(std::size_t(faces + internal));  // the larger first (see checkPolyMeshCells)
  r.starts = unwrittenArray<std::uint32_t>(std::size_t(nCells) + 1);
  std::uint32_t* starts = r.starts.get();
  std::uint32_t* list = r.faces.get();
#pragma omp parallel
  {
    int threads = 1, thread = 0;
#ifdef _OPENMP
    threads = omp_get_num_threads();
    thread = omp_get_thread_num();
#endif
    const std::int32_t first = std::int32_t(nCells * thread / threads);
    const std::int32_t last = std::int32_t(nCells * (thread + 1) / threads);
    const std::uint32_t span = std::uint32_t(last - first);
    for (std::int32_t c = first; c < last; ++c) starts[c + 1] = 0;
    forEachFaceOfCells(owner, neighbour, internal, faces, 0, internal, first, span,
                       [&](std::int64_t c, std::uint32_t) { ++starts[first + c + 1]; });
#pragma omp barrier
#pragma omp single
    {
      starts[0] = 0;
      for (std::int64_t c = 0; c < nCells; ++c) starts[c + 1] += starts[c];
    }
    // starts[c] is the cursor of cell c while the list fills (it ends at starts[c + 1]'s old value).
    std::vector<std::uint32_t> cursor(starts + first, starts + last);
    forEachFaceOfCells(owner, neighbour, internal, faces, 0, internal, first, span,
                       [&](std::int64_t c, std::uint32_t entry) { list[cursor[std::size_t(c)]++] = entry; });
  }
  return r;
}

// How the mesh numbers its cells: the largest |neighbour - owner| of an internal face, and whether
// the internal faces come in the order of their owners (as OpenFOAM orders them).
struct MeshOrder {
  std::int64_t bandwidth = 0;
  bool ownersInOrder = true;
};

MeshOrder meshOrderOf(const PolyMeshCells& cells) {
  const std::int64_t internal = std::int64_t(cells.neighbour.size());
  const Labels owner(cells.owner.bytes()), neighbour(cells.neighbour.bytes());
  std::int64_t bandwidth = 0, outOfOrder = 0;
#pragma omp parallel for reduction(max : bandwidth) reduction(+ : outOfOrder) schedule(static)
  for (std::int64_t f = 0; f < internal; ++f) {
    const std::int32_t own = owner[f];
    bandwidth = std::max(bandwidth, std::abs(std::int64_t(neighbour[f]) - own));
    outOfOrder += f + 1 < internal && owner[f + 1] < own ? 1 : 0;
  }
  return {bandwidth, outOfOrder == 0};
}

// The faces of the cells of one sweep, as CellFaces holds them for the whole mesh (each cell's in
// increasing face order, kNeighbourSide marking the neighbour's side), made for the sweep alone
// where the internal faces come in their owners' order: a cell's faces are then among the internal
// faces whose owners lie within the bandwidth of the sweep's cells, found by bisection, and the
// boundary faces. Made by the thread that checks the sweep, in memory it keeps for its next
// sweep: about 28 bytes per cell of one sweep, where CellFaces takes 28 per cell of the mesh.
class SweepFaces {
 public:
  // The lists of the whole mesh (a mesh whose internal faces are not in their owners' order).
  explicit SweepFaces(const CellFaces* all) : all_(all) {
    if (all_ != nullptr) starts_ = all_->starts.get(), faces_ = all_->faces.get();
  }
  // Makes the lists of cells [first, last) (nothing to make when they are the whole mesh's).
  void make(const PolyMeshCells& cells, std::int64_t bandwidth, std::int64_t first, std::int64_t last);
  std::uint32_t start(std::int64_t c) const { return starts_[c - first_]; }  // cell c's first in faces()
  std::uint32_t end(std::int64_t c) const { return starts_[c - first_ + 1]; }
  std::uint32_t operator[](std::uint32_t k) const { return faces_[k]; }

 private:
  template <class T>
  static T* atLeast(std::unique_ptr<T[]>& buffer, std::size_t& size, std::size_t needed) {
    if (size < needed) buffer = std::make_unique_for_overwrite<T[]>(size = needed);
    return buffer.get();
  }
  const CellFaces* all_;
  const std::uint32_t* starts_ = nullptr;
  const std::uint32_t* faces_ = nullptr;
  std::int64_t first_ = 0;
  std::unique_ptr<std::uint32_t[]> ownStarts_, ownFaces_, cursor_;
  std::size_t startsSize_ = 0, facesSize_ = 0, cursorSize_ = 0;
};

void SweepFaces::make(const PolyMeshCells& cells, std::int64_t bandwidth, std::int64_t first, std::int64_t last) {
  if (all_ != nullptr) return;
  const std::int64_t internal = std::int64_t(cells.neighbour.size()), faces = cells.faceCount();
  const Labels owner(cells.owner.bytes()), neighbour(cells.neighbour.bytes());
  const std::uint32_t span = std::uint32_t(last - first);
  // The internal faces owned by cells [first - bandwidth, last + bandwidth): every internal face of
  // a cell of the sweep is among them.
  auto ownedFrom = [&](std::int64_t cell) {
    std::int64_t lo = 0, hi = internal;  // the first internal face owned by `cell` or a later cell
    while (lo < hi) {
      const std::int64_t mid = lo + (hi - lo) / 2;
      if (owner[mid] < cell) lo = mid + 1;
      else hi = mid;
    }
    return lo;
  };
  const std::int64_t from = ownedFrom(first - bandwidth), to = ownedFrom(last + bandwidth);
  std::uint32_t* starts = atLeast(ownStarts_, startsSize_, std::size_t(span) + 1);
  std::fill(starts, starts + span + 1, 0u);
  forEachFaceOfCells(owner, neighbour, internal, faces, from, to, first, span,
                     [&](std::int64_t c, std::uint32_t) { ++starts[c + 1]; });
  for (std::uint32_t c = 0; c < span; ++c) starts[c + 1] += starts[c];
  std::uint32_t* cursor = atLeast(cursor_, cursorSize_, std::size_t(span));
  std::copy(starts, starts + span, cursor);
  std::uint32_t* list = atLeast(ownFaces_, facesSize_, std::max<std::size_t>(1, starts[span]));
  forEachFaceOfCells(owner, neighbour, internal, faces, from, to, first, span,
                     [&](std::int64_t c, std::uint32_t entry) { list[cursor[c]++] = entry; });
  starts_ = starts;
  faces_ = list;
  first_ = first;
}

// Per block of cells: what the volumes add to the result.
struct VolumeShare {
  double min = std::numeric_limits<double>::infinity();
  double max = -std::numeric_limits<double>::infinity();
  double total = 0.0;
  std::int64_t negative = 0;
};

// Per sweep of cells or block of faces: what the face checks add to the result.
struct FaceShare {
  double minPyramid = std::numeric_limits<double>::infinity();
  double minCosine = 1.0;
  double sumCosines = 0.0;
  double maxSkewness = 0.0;
  std::int64_t incorrectlyOriented = 0;
};

// The cells are checked in sweeps: runs of consecutive cells (whole blocks of kBlock, about an
// eighth of the mesh and at least 65,536 cells, so that the split depends on the mesh alone, not
// on the number of threads), each visited in order by one thread.
std::int64_t sweepLength(std::int64_t cellCount) {
  const std::int64_t blocks = (cellCount + kBlock - 1) / kBlock;
  return std::max<std::int64_t>(8, (blocks + 7) / 8) * kBlock;
}

// The geometry of the faces a sweep computed last, by face index modulo the window's size. A sweep computes
// a face when it meets the first of its cells and reads it here at the second, which in a mesh in
// OpenFOAM's upper-triangular order comes a few layers of cells later (a 215^3 cube: about 140,000
// faces later). A face no longer here (another mesh order) is computed again, to the same bits.
struct FaceCache {
  static constexpr std::size_t kMostSlots = std::size_t(1) << 18;  // 13.6 MB per thread
  // No more slots than the mesh has faces (a small mesh's check allocates little).
  explicit FaceCache(std::int64_t faces)
      : mask(std::bit_ceil(std::clamp<std::size_t>(std::size_t(faces), 1, kMostSlots)) - 1),
        face(mask + 1, -1), geometry(mask + 1) {}
  std::size_t slot(std::int64_t f) const { return std::size_t(f) & mask; }
  bool holds(std::int64_t f) const { return face[slot(f)] == f; }
  void store(std::int64_t f, const FaceGeometry& g) {
    face[slot(f)] = std::int32_t(f);
    geometry[slot(f)] = g;
  }
  std::size_t mask;
  std::vector<std::int32_t> face;  // the face in each slot, -1 for none (faces number below 2^31)
  std::vector<FaceGeometry> geometry;
};

// Where the check keeps the cell centres. A face is checked at the later of its two cells in a
// sweep, so a sweep needs back no centre further than the mesh's bandwidth (the largest
// |neighbour - owner|): where that is small beside the mesh (OpenFOAM numbers its cells so, a
// 215^3 cube's bandwidth is 46,225 cells), each sweep keeps the centres of its last cells in a
// window of its own (kept by cell index modulo its size, larger than the bandwidth and a batch of
// cells), and the centres of its first and last `bandwidth` cells, the only ones a face between
// two sweeps can have, for the check of those faces; 24 bytes per cell of the mesh are then
// never written. Else (a mesh numbered otherwise) one row per cell.
class CentreStore {
 public:
  CentreStore(std::int64_t cellCount, std::int64_t bandwidth, std::int64_t sweep, std::int64_t sweeps, std::int64_t batch) {
    const std::int64_t needed = bandwidth + batch + 1;
    window_ = std::bit_ceil(std::uint64_t(std::max<std::int64_t>(needed, 1)));
    windowed_ = needed <= kMostWindow && std::int64_t(window_) * 8 <= cellCount;
    if (!windowed_) {
      all_ = std::make_unique_for_overwrite<double[]>(std::size_t(cellCount) * 3);
      return;
    }
    border_ = std::max<std::int64_t>(bandwidth, 1);
    sweep_ = sweep;
    cellCount_ = cellCount;
    borders_ = std::make_unique_for_overwrite<double[]>(std::size_t(sweeps * 2 * border_ * 3));
  }
  bool windowed() const { return windowed_; }
  std::size_t windowCells() const { return window_; }
  // Where the sweep running on a thread with `window` (windowCells() x 3 doubles) keeps cell c's centre.
  double* inSweep(double* window, std::int64_t c) const {
    return windowed_ ? window + (std::uint64_t(c) & (window_ - 1)) * 3 : all_.get() + c * 3;
  }
  // After a sweep computed cell c's centre (at inSweep): kept for the faces between sweeps too.
  void keep(std::int64_t c, const double* centre) {
    if (!windowed_) return;
    if (double* at = border(c)) std::memcpy(at, centre, 3 * sizeof(double));
  }
  // Cell c's centre for a face between two sweeps (c is then within the bandwidth of its sweep's ends).
  const double* betweenSweeps(std::int64_t c) const { return windowed_ ? border(c) : all_.get() + c * 3; }

 private:
  static constexpr std::int64_t kMostWindow = std::int64_t(1) << 20;  // 24 MiB per thread
  // Cell c's row among its sweep's first and last `border_` cells, null for another cell.
  double* border(std::int64_t c) const {
    const std::int64_t s = c / sweep_, first = s * sweep_, last = std::min(cellCount_, first + sweep_);
    if (c < first + border_) return borders_.get() + ((s * 2) * border_ + (c - first)) * 3;
    if (c >= last - border_) return borders_.get() + ((s * 2 + 1) * border_ + (c - (last - border_))) * 3;
    return nullptr;
  }
  bool windowed_ = false;
  std::uint64_t window_ = 1;
  std::int64_t border_ = 0, sweep_ = 1, cellCount_ = 0;
  std::unique_ptr<double[]> all_;      // one row per cell, when not windowed
  std::unique_ptr<double[]> borders_;  // per sweep: its first border_ cells' centres, then its last border_ cells'
};

}  // namespace

CellQuality checkPolyMeshCells(const Eigen::MatrixX3d& points, const PolyMeshCells& cells,
                               const CellQualityOptions& options) {
  const PointColumns p(points);
  CellQuality q;
  const std::int64_t faces = cells.faceCount();
  const std::int64_t internal = std::int64_t(cells.neighbour.size());
  const std::int64_t nCells = cells.cellCount;
  q.cellCount = nCells;
  q.faceCount = faces;

  // The arrays from the largest to the smallest: a process that keeps freed memory for reuse
  // (ffdkit-cli) then fits each into a block freed before instead of growing its heap for one
  // that no longer fits after a smaller one took part of the block.
  const MeshOrder order = meshOrderOf(cells);
  const std::int64_t sweep = sweepLength(nCells);
  const std::int64_t sweeps = (nCells + sweep - 1) / sweep;
  // Each cell's faces: made sweep by sweep (SweepFaces) where the internal faces are in their
  // owners' order and the bandwidth is small beside a sweep (each sweep then reads the owner and
  // neighbour lists of little more than its own cells), else the whole mesh's lists.
  const bool bySweep = order.ownersInOrder && order.bandwidth <= sweep / 4;
  const CellFaces allCellFaces = bySweep ? CellFaces{} : cellFacesOf(cells);
  // The cells' centres, written first by the sweeps, on every core. A sweep computes a batch of
  // cells (at most FaceLanes::kLanes) before it checks their faces.
  CentreStore centres(nCells, order.bandwidth, sweep, sweeps, FaceLanes::kLanes);
  std::vector<std::uint8_t> bad(std::size_t(nCells), 0);
  const std::int64_t blocks = (nCells + kBlock - 1) / kBlock;
  std::vector<VolumeShare> volumeShares(static_cast<std::size_t>(blocks));
  std::vector<FaceShare> sweepShares(static_cast<std::size_t>(sweeps));
  const MeshLabels m(cells);
  const Labels owner = m.owner, neighbour = m.neighbour;
  auto markBad = [&bad](std::int32_t cell) { std::atomic_ref<std::uint8_t>(bad[std::size_t(cell)]).store(1, std::memory_order_relaxed); };

  // Each face's pyramids about the two cell centres, its non-orthogonality and skewness
  // (primitiveMeshCheck.C: checkFacePyramids, checkFaceOrthogonality, checkFaceSkewness): the faces
  // put in `lanes` computed together (faceCheckLanes), then added to `share` in lane order, so
  // every sum and count is what checking them one by one in that order gives.
  auto checkFaces = [&](detail::FaceCheckLanes& lanes, FaceShare& share) {
    detail::faceCheckLanes(lanes);
    for (int l = 0; l < lanes.count; ++l) {
      const std::int64_t f = lanes.face[l];
      const double ownPyramid = lanes.ownPyramid[l];
      share.minPyramid = std::min(share.minPyramid, ownPyramid);
      if (ownPyramid < -kSmall) {
        ++share.incorrectlyOriented;
        markBad(owner[f]);
      }
      if (f < internal) {
        const double neiPyramid = lanes.neiPyramid[l];
        share.minPyramid = std::min(share.minPyramid, neiPyramid);
        if (neiPyramid < -kSmall) {
          ++share.incorrectlyOriented;
          markBad(neighbour[f]);
        }
        share.minCosine = std::min(share.minCosine, lanes.cosine[l]);
        share.sumCosines += lanes.cosine[l];
      }
      // The largest skewness is all the result keeps of them: a face whose bound is no more than
      // the largest so far cannot change it, and its points are not read again.
      double skewness = 0.0;
      if (lanes.quadInside[l]) {
        if (!(lanes.skewnessBound[l] <= share.maxSkewness)) skewness = quadSkewness(lanes, l, p, m, f);
      } else {
        const Eigen::Vector3d ownCentre(lanes.ocx[l], lanes.ocy[l], lanes.ocz[l]);
        const Eigen::Vector3d neiCentre(lanes.ncx[l], lanes.ncy[l], lanes.ncz[l]);
        skewness = faceSkewness(p, m, f, {{lanes.fcx[l], lanes.fcy[l], lanes.fcz[l]}, {lanes.fax[l], lanes.fay[l], lanes.faz[l]}},
                                ownCentre, f < internal ? &neiCentre : nullptr);
      }
      share.maxSkewness = std::max(share.maxSkewness, skewness);
    }
    lanes.count = 0;
  };
  // Face f, of geometry `g`, to check with the next faces (its cells' centres are known:
  // centreOf(cell) gives them).
  auto checkFace = [&](detail::FaceCheckLanes& lanes, std::int64_t f, const FaceGeometry& g, FaceShare& share,
                       const auto& centreOf) {
    if (lanes.count == detail::FaceCheckLanes::kLanes) checkFaces(lanes, share);
    addFaceCheck(lanes, m, f, g, centreOf(owner[f]), f < internal ? centreOf(neighbour[f]) : nullptr);
  };

  // One pass over the cells, sweep by sweep (OpenFOAM: primitiveMeshCellCentresAndVols.C, then
  // the face checks): each cell's volume and centre from the pyramids of its faces about a first
  // estimate, the average of its face centres, its faces added in face order (as OpenFOAM's loops
  // over owner and neighbour add them for each cell); then the checks of those of its faces whose
  // other cell the sweep has done (or that have none). A face between two sweeps is checked
  // after them all.
#pragma omp parallel
  {
    auto lanes = std::make_unique<FaceLanes>();
    auto checks = std::make_unique<detail::FaceCheckLanes>();
    auto cache = std::make_unique<FaceCache>(faces);
    // This thread's window of centres (CentreStore), not written before the sweep writes it.
    const auto window = std::make_unique_for_overwrite<double[]>(centres.windowed() ? centres.windowCells() * 3 : 0);
    auto centreOf = [&](std::int64_t cell) -> const double* { return centres.inSweep(window.get(), cell); };
    SweepFaces cellFaces(bySweep ? nullptr : &allCellFaces);
    auto faceOf = [&](std::uint32_t k) { return std::int64_t(cellFaces[k] & ~CellFaces::kNeighbourSide); };
    std::int64_t laneFace[FaceLanes::kLanes];
    // The geometry of the faces of the cell addCell did last, in its face order: fetched from the
    // window once, read by the cell's two sums and by its face checks.
    std::vector<FaceGeometry> cellGeometry;
    auto addCell = [&](std::int64_t c) {
      VolumeShare& share = volumeShares[std::size_t(c / kBlock)];
      const std::uint32_t begin = cellFaces.start(c), end = cellFaces.end(c);
      if (cellGeometry.size() < end - begin) cellGeometry.resize(end - begin);
      Eigen::Vector3d estimate = Eigen::Vector3d::Zero();
      for (std::uint32_t k = begin; k < end; ++k) {
        const std::int64_t f = faceOf(k);
        const std::size_t slot = cache->slot(f);
        FaceGeometry& g = cellGeometry[k - begin];
        if (cache->face[slot] == f) g = cache->geometry[slot];
        else g = faceGeometry(p, m, f);
        estimate += g.centre;
      }
      estimate /= double(std::max<std::uint32_t>(1, end - begin));
      // 3 x the volume, and the centre weighted by it.
      Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
      double volume3 = 0.0;
      for (std::uint32_t k = begin; k < end; ++k) {
        const FaceGeometry& g = cellGeometry[k - begin];
        const double sign = (cellFaces[k] & CellFaces::kNeighbourSide) != 0 ? -1.0 : 1.0;
        const double pyramid3 = sign * g.area.dot(g.centre - estimate);
        weighted += pyramid3 * (0.75 * g.centre + 0.25 * estimate);
        volume3 += pyramid3;
      }
      double* centre = centres.inSweep(window.get(), c);
      Eigen::Map<Eigen::Vector3d>{centre} = std::abs(volume3) > kVerySmall ? Eigen::Vector3d(weighted / volume3) : estimate;
      centres.keep(c, centre);
      const double volume = volume3 / 3.0;
      if (volume < kVerySmall) {
        ++share.negative;
        bad[std::size_t(c)] = 1;
      }
      share.min = std::min(share.min, volume);
      share.max = std::max(share.max, volume);
      share.total += volume;
    };
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t s = 0; s < sweeps; ++s) {
      const std::int64_t first = s * sweep, last = std::min(nCells, first + sweep);
      FaceShare& faceShare = sweepShares[std::size_t(s)];
      cellFaces.make(cells, order.bandwidth, first, last);
      for (std::int64_t c = first; c < last;) {
        // A batch: as many whole cells (up to FaceLanes::kLanes) as the faces not yet computed of
        // fit the lanes; a cell with more such faces than lanes on its own, face by face.
        const std::int64_t batch = c;
        lanes->clear();
        while (c < last && c - batch < FaceLanes::kLanes) {
          const std::uint32_t begin = cellFaces.start(c), end = cellFaces.end(c);
          int need = 0;
          for (std::uint32_t k = begin; k < end; ++k) need += cache->holds(faceOf(k)) ? 0 : 1;
          if (lanes->count + need > FaceLanes::kLanes) {
            if (c > batch) break;
            for (std::uint32_t k = begin; k < end; ++k)
              if (!cache->holds(faceOf(k))) cache->store(faceOf(k), faceGeometry(p, m, faceOf(k)));
          } else {
            for (std::uint32_t k = begin; k < end; ++k) {
              const std::int64_t f = faceOf(k);
              if (cache->holds(f)) continue;
              laneFace[lanes->count] = f;
              lanes->add(p, m, f);
              cache->face[cache->slot(f)] = std::int32_t(f);  // its lane's result is stored below
            }
          }
          ++c;
        }
        lanes->compute();
        for (int l = 0; l < lanes->count; ++l) cache->store(laneFace[l], (*lanes)[l]);
        for (std::int64_t d = batch; d < c; ++d) {
          addCell(d);
          const std::uint32_t begin = cellFaces.start(d);
          for (std::uint32_t k = begin; k < cellFaces.end(d); ++k) {
            const std::int64_t f = faceOf(k);
            const std::int64_t other = (cellFaces[k] & CellFaces::kNeighbourSide) != 0 ? owner[f]
                                       : f < internal                                      ? neighbour[f]
                                                                                           : -1;
            if (other < 0 || (other >= first && other < d)) checkFace(*checks, f, cellGeometry[k - begin], faceShare, centreOf);
          }
        }
      }
      checkFaces(*checks, faceShare);
    }
  }

  // The faces between two sweeps, in blocks of faces. A cell's sweep by a table of its block's
  // (a sweep is whole blocks of kBlock cells, a power of 2): no division per face.
  const std::int64_t faceBlocks = sweeps > 1 ? (internal + kBlock - 1) / kBlock : 0;
  std::vector<std::int32_t> sweepOfBlock(static_cast<std::size_t>(blocks));
  for (std::int64_t b = 0; b < blocks; ++b) sweepOfBlock[std::size_t(b)] = std::int32_t(b * kBlock / sweep);
  auto sweepOf = [&](std::int32_t cell) { return sweepOfBlock[std::size_t(cell) >> kBlockBits]; };
  std::vector<FaceShare> betweenShares(static_cast<std::size_t>(faceBlocks));
  auto betweenCentreOf = [&](std::int64_t cell) { return centres.betweenSweeps(cell); };
  if (faceBlocks > 0) {
#pragma omp parallel
    {
      auto lanes = std::make_unique<FaceLanes>();
      auto checks = std::make_unique<detail::FaceCheckLanes>();
      std::int64_t laneFace[FaceLanes::kLanes];
#pragma omp for schedule(dynamic, 4)
      for (std::int64_t b = 0; b < faceBlocks; ++b) {
        FaceShare& share = betweenShares[std::size_t(b)];
        const std::int64_t last = std::min(internal, (b + 1) * kBlock);
        for (std::int64_t f = b * kBlock; f < last;) {
          lanes->clear();
          for (; f < last && lanes->count < FaceLanes::kLanes; ++f) {
            if (sweepOf(owner[f]) == sweepOf(neighbour[f])) continue;
            laneFace[lanes->count] = f;
            lanes->add(p, m, f);
          }
          lanes->compute();
          for (int l = 0; l < lanes->count; ++l) checkFace(*checks, laneFace[l], (*lanes)[l], share, betweenCentreOf);
        }
        checkFaces(*checks, share);
      }
    }
  }

  q.minVolume = std::numeric_limits<double>::infinity();
  q.maxVolume = -std::numeric_limits<double>::infinity();
  for (const VolumeShare& share : volumeShares) {
    q.negativeVolumeCells += share.negative;
    q.minVolume = std::min(q.minVolume, share.min);
    q.maxVolume = std::max(q.maxVolume, share.max);
    q.totalVolume += share.total;
  }
  q.minPyramidVolume = std::numeric_limits<double>::infinity();
  double sumCosines = 0.0;
  double minCosine = 1.0;
  for (const auto* shares : {&sweepShares, &betweenShares})
    for (const FaceShare& share : *shares) {
      q.minPyramidVolume = std::min(q.minPyramidVolume, share.minPyramid);
      q.incorrectlyOrientedFaces += share.incorrectlyOriented;
      minCosine = std::min(minCosine, share.minCosine);
      sumCosines += share.sumCosines;
      q.maxSkewness = std::max(q.maxSkewness, share.maxSkewness);
    }
  // The largest angle is the smallest cosine's (acos decreases): one acos, not one per face.
  if (internal > 0) q.maxNonOrthogonality = std::acos(std::clamp(minCosine, -1.0, 1.0)) * 180.0 / std::numbers::pi;
  // checkMesh's average: the angle of the mean cosine (not the mean angle).
  if (internal > 0)
    q.meanNonOrthogonality = std::acos(std::clamp(sumCosines / double(internal), -1.0, 1.0)) * 180.0 / std::numbers::pi;
  if (faces == 0) q.minPyramidVolume = 0.0;
  if (nCells == 0) q.minVolume = q.maxVolume = 0.0;
  for (std::size_t c = 0; c < bad.size(); ++c)
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
