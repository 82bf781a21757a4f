#include "ffdkit/ffd/box_bernstein_deform.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "ffdkit/ffd/box_lattice_options.h"
#include "ffdkit/ffd/lattice_error.h"
#include "vector_clones.h"

namespace ffdkit::ffd {
namespace {

constexpr int kLanes = 8;
constexpr int kMaxCount = 33;  // Bernstein degree <= 32, as AxisSpline allows
// Below this many points a parallel region costs more than it saves; also the chunk of points
// one thread takes at a time (dynamic: the machine may be shared).
constexpr Eigen::Index kChunk = 16384;

// Eight lanes of doubles (one AVX-512 register, two AVX2 or four SSE2 registers, by clone).
typedef double Lane __attribute__((vector_size(kLanes * sizeof(double))));

// Everything the kernel reads, flattened.
struct Kernel {
  double inverse[9];  // frame.linear()^-1, row-major
  double origin[3];   // frame.translation()
  double lo, hi;      // inside: lo <= s <= hi per axis
  int counts[3];
  // The (j, k) rows of the lattice that hold a non-zero displacement, and their l world
  // displacements frame.linear() * d_ijk (i = 0..l-1), one array per coordinate.
  int rowCount;
  const int* rowJ;
  const int* rowK;
  const double* dx;
  const double* dy;
  const double* dz;
  const double* q;
  Eigen::Index qRow, qCol;  // strides of the input, in doubles
  double* out;
  Eigen::Index outRow, outCol;
  bool inPlace;  // out is q (same data and strides): nothing to copy for outside points
};

FFDKIT_INLINE Lane splat(double x) { return Lane{} + x; }

// The degree+1 Bernstein values B_i^n(t), i = 0..n, of eight parameters at once, with de
// Casteljau's triangle as bernsteinBasis() does (Sederberg & Parry 1986, eq. 1). C > 0 fixes the
// count n+1 at compile time (full unrolling).
template <int C>
FFDKIT_INLINE void bernsteinLanes(int count, Lane t, Lane* b) {
  const int n = (C > 0 ? C : count) - 1;
  const Lane s = 1.0 - t;
  b[0] = splat(1.0);
  for (int r = 1; r <= n; ++r) {
    b[r] = t * b[r - 1];
    for (int i = r - 1; i >= 1; --i) b[i] = s * b[i] + t * b[i - 1];
    b[0] = s * b[0];
  }
}

// The displacement sum_ijk B_i(su) B_j(sv) B_k(sw) D_ijk of eight points (world units), over the
// non-zero rows (j, k) only: contract i first (l multiply-adds per coordinate), then weight the
// row by B_j B_k.
template <int C>
FFDKIT_INLINE void displacementLanes(const Kernel& k, Lane su, Lane sv, Lane sw, Lane& dx, Lane& dy, Lane& dz) {
  const int cu = C > 0 ? C : k.counts[0];
  Lane bu[C > 0 ? C : kMaxCount], bv[C > 0 ? C : kMaxCount], bw[C > 0 ? C : kMaxCount];
  bernsteinLanes<C>(k.counts[0], su, bu);
  bernsteinLanes<C>(k.counts[1], sv, bv);
  bernsteinLanes<C>(k.counts[2], sw, bw);
  dx = dy = dz = splat(0.0);
  const double* Dx = k.dx;
  const double* Dy = k.dy;
  const double* Dz = k.dz;
  for (int row = 0; row < k.rowCount; ++row, Dx += cu, Dy += cu, Dz += cu) {
    Lane ax = bu[0] * Dx[0], ay = bu[0] * Dy[0], az = bu[0] * Dz[0];
    for (int i = 1; i < cu; ++i) {
      ax += bu[i] * Dx[i];
      ay += bu[i] * Dy[i];
      az += bu[i] * Dz[i];
    }
    const Lane weight = bv[k.rowJ[row]] * bw[k.rowK[row]];
    dx += weight * ax;
    dy += weight * ay;
    dz += weight * az;
  }
}

// Inside points waiting for a full block of kLanes: their box coordinates (su, sv, sw), input
// point (x, y, z) and row. Points are appended branch-free (the slot is written whatever the
// point, the size grows only for an inside one), so at most 2 kLanes - 1 are ever held.
struct Queue {
  alignas(64) double value[6][2 * kLanes] = {};
  Eigen::Index row[2 * kLanes] = {};
  int size = 0;
};

FFDKIT_INLINE Lane loadLane(const double* p) {
  Lane x;
  __builtin_memcpy(&x, p, sizeof(Lane));
  return x;
}

// Deforms the first `count` queued points (all inside) and writes them to their rows of out.
template <int C>
FFDKIT_INLINE void flushQueue(const Kernel& k, Queue& q, int count) {
  Lane dx, dy, dz;
  displacementLanes<C>(k, loadLane(q.value[0]), loadLane(q.value[1]), loadLane(q.value[2]), dx, dy, dz);
  const Lane ox = loadLane(q.value[3]) + dx, oy = loadLane(q.value[4]) + dy, oz = loadLane(q.value[5]) + dz;
  for (int l = 0; l < count; ++l) {
    double* o = k.out + q.row[l] * k.outRow;
    o[0] = ox[l];
    o[k.outCol] = oy[l];
    o[2 * k.outCol] = oz[l];
  }
  // Move the remainder (slots kLanes .. 2 kLanes - 1, whatever their use) to the front.
  for (int c = 0; c < 6; ++c) __builtin_memcpy(q.value[c], q.value[c] + kLanes, sizeof(Lane));
  __builtin_memcpy(q.row, q.row + kLanes, kLanes * sizeof(Eigen::Index));
  q.size -= count;
}

// Writes the rows r0 .. r0+count-1 of out (packed rows: one contiguous store).
FFDKIT_INLINE void storeRows(const Kernel& k, Eigen::Index r0, int count, const double* x, const double* y,
                             const double* z) {
  if (k.outRow == 3 && k.outCol == 1 && count == kLanes) {
    double packed[3 * kLanes];
    for (int l = 0; l < kLanes; ++l) {
      packed[3 * l] = x[l];
      packed[3 * l + 1] = y[l];
      packed[3 * l + 2] = z[l];
    }
    // Three vector stores (a plain memcpy of the 192 bytes becomes `rep movs`, slow to start).
    for (int v = 0; v < 3; ++v) {
      Lane part;
      __builtin_memcpy(&part, packed + v * kLanes, sizeof(Lane));
      __builtin_memcpy(k.out + 3 * r0 + v * kLanes, &part, sizeof(Lane));
    }
    return;
  }
  for (int l = 0; l < count; ++l) {
    double* o = k.out + (r0 + l) * k.outRow;
    o[0] = x[l];
    o[k.outCol] = y[l];
    o[2 * k.outCol] = z[l];
  }
}

// One block of up to kLanes points starting at row r0 (count of them real; the other lanes repeat
// the last point and are not stored): box coordinates and the inside test, then
// - no point inside (or nothing displaced): out = q;
// - every point inside (the usual case in a coherent mesh or a box around the object): the sum
//   runs on the block itself and out is written once;
// - some inside: out = q, and the inside points are queued for a full block of inside points.
// insideLanes[l] counts the inside points of lane l.
// Plain arrays and loops the compiler vectorises, not Lane comparisons: GCC 12 splits comparisons
// of vector-extension types into scalar ones inside target_clones functions.
template <int C>
FFDKIT_INLINE void scanBlock(const Kernel& k, Eigen::Index r0, int count, Queue& q, std::int64_t* insideLanes) {
  double x[kLanes], y[kLanes], z[kLanes];
  if (k.qRow == 3 && k.qCol == 1 && count == kLanes) {
    // Packed rows (numpy's C order): one contiguous load, de-interleaved.
    double packed[3 * kLanes];
    __builtin_memcpy(packed, k.q + 3 * r0, sizeof(packed));
    for (int l = 0; l < kLanes; ++l) {
      x[l] = packed[3 * l];
      y[l] = packed[3 * l + 1];
      z[l] = packed[3 * l + 2];
    }
  } else {
    for (int l = 0; l < kLanes; ++l) {
      const double* p = k.q + (r0 + std::min(l, count - 1)) * k.qRow;
      x[l] = p[0];
      y[l] = p[k.qCol];
      z[l] = p[2 * k.qCol];
    }
  }
  double su[kLanes], sv[kLanes], sw[kLanes];
  std::int64_t in[kLanes];
  const double lo = k.lo, hi = k.hi;
  for (int l = 0; l < kLanes; ++l) {
    const double px = x[l] - k.origin[0], py = y[l] - k.origin[1], pz = z[l] - k.origin[2];
    su[l] = k.inverse[0] * px + k.inverse[1] * py + k.inverse[2] * pz;
    sv[l] = k.inverse[3] * px + k.inverse[4] * py + k.inverse[5] * pz;
    sw[l] = k.inverse[6] * px + k.inverse[7] * py + k.inverse[8] * pz;
    // NaN compares false: outside. Non-short-circuit &, so that the loop vectorises.
    in[l] = (su[l] >= lo) & (su[l] <= hi) & (sv[l] >= lo) & (sv[l] <= hi) & (sw[l] >= lo) & (sw[l] <= hi) & (l < count);
  }
  std::int64_t inside = 0;
  for (int l = 0; l < kLanes; ++l) {
    insideLanes[l] += in[l];
    inside += in[l];
  }
  if (k.rowCount == 0 || inside == 0) {
    if (!k.inPlace) storeRows(k, r0, count, x, y, z);
    return;
  }
  if (inside == count) {
    Lane dx, dy, dz;
    displacementLanes<C>(k, loadLane(su), loadLane(sv), loadLane(sw), dx, dy, dz);
    const Lane ox = loadLane(x) + dx, oy = loadLane(y) + dy, oz = loadLane(z) + dz;
    double rx[kLanes], ry[kLanes], rz[kLanes];
    __builtin_memcpy(rx, &ox, sizeof(Lane));
    __builtin_memcpy(ry, &oy, sizeof(Lane));
    __builtin_memcpy(rz, &oz, sizeof(Lane));
    storeRows(k, r0, count, rx, ry, rz);
    return;
  }
  if (!k.inPlace) storeRows(k, r0, count, x, y, z);
  for (int l = 0; l < count; ++l) {
    const int slot = q.size;
    q.value[0][slot] = su[l];
    q.value[1][slot] = sv[l];
    q.value[2][slot] = sw[l];
    q.value[3][slot] = x[l];
    q.value[4][slot] = y[l];
    q.value[5][slot] = z[l];
    q.row[slot] = r0 + l;
    q.size += static_cast<int>(in[l]);
  }
}

template <int C>
FFDKIT_INLINE Eigen::Index deformRangeT(const Kernel& k, Eigen::Index begin, Eigen::Index end) {
  std::int64_t insideLanes[kLanes] = {};
  Queue q;
  for (Eigen::Index r = begin; r < end; r += kLanes) {
    scanBlock<C>(k, r, static_cast<int>(std::min<Eigen::Index>(kLanes, end - r)), q, insideLanes);
    if (q.size >= kLanes) flushQueue<C>(k, q, kLanes);
  }
  if (q.size > 0) flushQueue<C>(k, q, q.size);
  Eigen::Index inside = 0;
  for (int l = 0; l < kLanes; ++l) inside += insideLanes[l];
  return inside;
}

FFDKIT_VECTOR_CLONES
Eigen::Index deformRange(const Kernel& k, Eigen::Index begin, Eigen::Index end) {
  const int c = k.counts[0];
  if (c == k.counts[1] && c == k.counts[2]) {
    switch (c) {
      case 2: return deformRangeT<2>(k, begin, end);
      case 3: return deformRangeT<3>(k, begin, end);
      case 4: return deformRangeT<4>(k, begin, end);
      case 5: return deformRangeT<5>(k, begin, end);
      default: break;
    }
  }
  return deformRangeT<-1>(k, begin, end);
}

std::string countsText(const Eigen::Vector3i& counts) {
  return "(" + std::to_string(counts[0]) + ", " + std::to_string(counts[1]) + ", " + std::to_string(counts[2]) + ")";
}

void checkInput(const BoxBernsteinLattice& lattice, Eigen::Index points, Eigen::Index outRows,
                const BoxBernsteinDeformOptions& options) {
  const Eigen::Vector3i& counts = lattice.counts;
  if ((counts.array() < 2).any() || (counts.array() > kMaxCount).any()) {
    throw LatticeError("box Bernstein lattice needs 2 to " + std::to_string(kMaxCount) + " points per axis, got " +
                       countsText(counts));
  }
  const Eigen::Index controls = Eigen::Index(counts[0]) * counts[1] * counts[2];
  const Eigen::MatrixX3d& d = lattice.displacements;
  if (d.rows() != 0 && d.rows() != controls) {
    throw LatticeError("box Bernstein lattice: expected " + std::to_string(controls) + " x 3 displacements for counts " +
                       countsText(counts) + ", got " + std::to_string(d.rows()) + " x 3");
  }
  for (Eigen::Index r = 0; r < d.rows(); ++r) {
    if (!d.row(r).allFinite()) {
      std::ostringstream os;
      os << "box Bernstein lattice: displacement " << r << " (i " << r % counts[0] << ", j " << (r / counts[0]) % counts[1]
         << ", k " << r / (Eigen::Index(counts[0]) * counts[1]) << ") is not finite (" << d(r, 0) << ", " << d(r, 1)
         << ", " << d(r, 2) << ")";
      throw LatticeError(os.str());
    }
  }
  if (!lattice.frame.matrix().allFinite()) throw LatticeError("box Bernstein lattice: frame is not finite");
  const double det = lattice.frame.linear().determinant();
  const double scale = lattice.frame.linear().norm();
  if (!(std::abs(det) > 1e-12 * scale * scale * scale)) {
    throw LatticeError("box Bernstein lattice: frame is singular (determinant " + std::to_string(det) + ")");
  }
  if (!(options.faceTolerance >= 0.0) || !std::isfinite(options.faceTolerance)) {
    throw LatticeError("boxBernsteinDeform: faceTolerance must be finite and >= 0, got " +
                       std::to_string(options.faceTolerance));
  }
  if (outRows != points) {
    throw LatticeError("boxBernsteinDeform: out has " + std::to_string(outRows) + " rows, expected " +
                       std::to_string(points) + " (one per input point)");
  }
}

}  // namespace

Lattice toLattice(const BoxBernsteinLattice& box) {
  BoxLatticeOptions options;
  options.counts = box.counts;
  options.bases = {AxisBasis::bernstein(), AxisBasis::bernstein(), AxisBasis::bernstein()};
  options.frame = box.frame;
  Lattice lattice = makeBoxLattice(options);
  if (box.displacements.size() > 0) lattice.setControlPoints(lattice.controlPoints() + box.displacements);
  return lattice;
}

BoxBernsteinDeformResult boxBernsteinDeform(const BoxBernsteinLattice& lattice, const StridedPoints& points,
                                            StridedPointsOut out, const BoxBernsteinDeformOptions& options) {
  checkInput(lattice, points.rows(), out.rows(), options);
  const Eigen::Vector3i& counts = lattice.counts;
  const int l = counts[0], m = counts[1], n = counts[2];

  // The non-zero rows (j, k) and their world displacements frame.linear() * d_ijk.
  std::vector<int> rowJ, rowK;
  std::vector<double> dx, dy, dz;
  const Eigen::Matrix3d linear = lattice.frame.linear();
  if (lattice.displacements.rows() != 0) {
    for (int k = 0; k < n; ++k) {
      for (int j = 0; j < m; ++j) {
        const Eigen::Index first = Eigen::Index(l) * (j + Eigen::Index(m) * k);
        const auto row = lattice.displacements.middleRows(first, l);
        if ((row.array() == 0.0).all()) continue;
        rowJ.push_back(j);
        rowK.push_back(k);
        for (int i = 0; i < l; ++i) {
          const Eigen::Vector3d world = linear * row.row(i).transpose();
          dx.push_back(world[0]);
          dy.push_back(world[1]);
          dz.push_back(world[2]);
        }
      }
    }
  }

  Kernel k{};
  const Eigen::Matrix3d inverse = linear.inverse();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) k.inverse[3 * r + c] = inverse(r, c);
    k.origin[r] = lattice.frame.translation()[r];
    k.counts[r] = counts[r];
  }
  k.lo = -options.faceTolerance;
  k.hi = 1.0 + options.faceTolerance;
  k.rowCount = static_cast<int>(rowJ.size());
  k.rowJ = rowJ.data();
  k.rowK = rowK.data();
  k.dx = dx.data();
  k.dy = dy.data();
  k.dz = dz.data();
  k.q = points.data();
  k.qRow = points.outerStride();
  k.qCol = points.innerStride();
  k.out = out.data();
  k.outRow = out.outerStride();
  k.outCol = out.innerStride();
  k.inPlace = k.out == k.q && k.outRow == k.qRow && k.outCol == k.qCol;

  BoxBernsteinDeformResult result;
  const Eigen::Index rows = points.rows();
  if (rows == 0) return result;
  const Eigen::Index chunks = (rows + kChunk - 1) / kChunk;
  Eigen::Index inside = 0;
  // Chunks of kChunk points (a multiple of kLanes) so that blocks never straddle two threads.
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : inside) if (options.parallel && chunks > 1)
  for (Eigen::Index c = 0; c < chunks; ++c) {
    inside += deformRange(k, c * kChunk, std::min(rows, (c + 1) * kChunk));
  }
  result.insidePoints = inside;
  return result;
}

}  // namespace ffdkit::ffd
