#include "ffdkit/ffd/deformer.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "deform_kernels.h"
#include "ffdkit/ffd/huge_pages.h"

namespace ffdkit::ffd {

namespace {

// Below this many points a parallel region costs more than it saves (thread wake-up, barriers).
constexpr Eigen::Index kParallelPoints = 16384;

// Per axis: cell -> knot span, and the control indices of each cell's window.
struct AxisTables {
  std::vector<int> span[3];
  std::vector<int> window[3];  // window[a][cell * (p+1) + r] = control index
};

AxisTables makeTables(const Lattice& lattice) {
  AxisTables t;
  for (int a = 0; a < 3; ++a) {
    const AxisSpline& axis = lattice.axis(a);
    for (int c = 0; c < axis.cellCount(); ++c) {
      t.span[a].push_back(axis.cellSpan(c));
      for (int r = 0; r <= axis.degree(); ++r) t.window[a].push_back(axis.controlIndex(c, r));
    }
  }
  return t;
}

void gatherWindow(const Lattice& lattice, const AxisTables& tables, const int cell[3], const Eigen::MatrixX3d& D,
                  std::vector<double>& W) {
  const int nu = lattice.axis(0).degree() + 1;
  const int nv = lattice.axis(1).degree() + 1;
  const int nw = lattice.axis(2).degree() + 1;
  const std::size_t size = static_cast<std::size_t>(nu) * nv * nw;
  W.resize(3 * size);
  std::size_t wi = 0;
  for (int c = 0; c < nw; ++c) {
    const int k = tables.window[2][cell[2] * nw + c];
    for (int b = 0; b < nv; ++b) {
      const int j = tables.window[1][cell[1] * nv + b];
      for (int a = 0; a < nu; ++a, ++wi) {
        const Eigen::Index f = lattice.index(tables.window[0][cell[0] * nu + a], j, k);
        W[wi] = D(f, 0);
        W[size + wi] = D(f, 1);
        W[2 * size + wi] = D(f, 2);
      }
    }
  }
}


int cellTotalOf(const Lattice& lattice) {
  return lattice.axis(0).cellCount() * lattice.axis(1).cellCount() * lattice.axis(2).cellCount();
}

std::size_t flatCell(const Lattice& lattice, const int cell[3]) {
  return cell[0] + static_cast<std::size_t>(lattice.axis(0).cellCount()) *
                       (cell[1] + static_cast<std::size_t>(lattice.axis(1).cellCount()) * cell[2]);
}

void unflatCell(const Lattice& lattice, std::size_t flat, int cell[3]) {
  const std::size_t cu = lattice.axis(0).cellCount(), cv = lattice.axis(1).cellCount();
  cell[0] = static_cast<int>(flat % cu);
  cell[1] = static_cast<int>((flat / cu) % cv);
  cell[2] = static_cast<int>(flat / (cu * cv));
}

// What the block kernels read per cell for one field D of world displacements (#control x 3):
// the power-form coefficient sets of the cells (lattices of degree <= 3, detail::powerBlock) or
// their gathered windows (Cox-de Boor, detail::denseBlock). Coefficient sets are precomputed once
// per call for the cells that have points to evaluate, in parallel, while they fit in
// max(1 MiB, 16 bytes per evaluated point); past that (a lattice of many more cells than
// points) each block computes its cell's set when the cell changes. Both give the same bits.
class CellFields {
 public:
  CellFields(const Lattice& lattice, const AxisTables& tables, const Eigen::MatrixX3d& D,
             Precision precision = Precision::Double)
      : lattice_(lattice), tables_(tables), D_(D), precision_(precision) {
    const int degrees[3] = {lattice.axis(0).degree(), lattice.axis(1).degree(), lattice.axis(2).degree()};
    K_ = detail::powerDegree(degrees);
    for (int a = 0; a < 3; ++a) {
      windowCounts_[a] = degrees[a] + 1;
      if (K_ >= 0) poly_[a] = detail::axisPolynomials(lattice.axis(a), K_);
    }
  }
  bool power() const { return K_ >= 0; }
  // Precision::Single on a power-form lattice: the kernels read float coefficient sets.
  bool single() const { return power() && precision_ == Precision::Single; }
  const detail::AxisPolynomials* polynomials(int axis) const { return power() ? &poly_[axis] : nullptr; }
  std::size_t setSize() const { return power() ? detail::coefficientSetSize(K_) : 0; }

  // Plans the table for the cells of `flats` (distinct flat indices), given `work` points to evaluate.
  void plan(std::vector<std::size_t> flats, Eigen::Index work) {
    if (!power()) return;
    const std::size_t bytes = flats.size() * setSize() * sizeof(double);
    if (bytes > std::max<std::size_t>(std::size_t(1) << 20, 16 * static_cast<std::size_t>(work))) return;
    slot_.assign(static_cast<std::size_t>(cellTotalOf(lattice_)), -1);
    for (std::size_t i = 0; i < flats.size(); ++i) slot_[flats[i]] = static_cast<std::int32_t>(i);
    flats_ = std::move(flats);
    table_.resize(flats_.size() * setSize());
    if (single()) tableSingle_.resize(table_.size());
  }
  // Fills the planned table; call from every thread of a parallel region (work-shared, ends with a barrier).
  void fillTable() {
    std::vector<double> window;
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(flats_.size()); ++i) {
      int cell[3];
      unflatCell(lattice_, flats_[i], cell);
      compute(cell, window, table_.data() + i * setSize());
      if (single()) round(table_.data() + i * setSize(), tableSingle_.data() + i * setSize());
    }
  }
  // One thread's access to the cells' data, caching the last cell computed outside the table.
  class Reader {
   public:
    explicit Reader(const CellFields& fields) : f_(fields) {}
    // Power: the coefficient set of `cell`; Cox-de Boor: the window (x, y, z blocks).
    const double* at(const int cell[3]) {
      if (!f_.slot_.empty()) return f_.table_.data() + f_.slot_[flatCell(f_.lattice_, cell)] * f_.setSize();
      if (!std::equal(cell, cell + 3, last_)) {
        if (f_.power()) {
          set_.resize(f_.setSize());
          f_.compute(cell, window_, set_.data());
        } else {
          gatherWindow(f_.lattice_, f_.tables_, cell, f_.D_, window_);
        }
        std::copy(cell, cell + 3, last_);
      }
      return f_.power() ? set_.data() : window_.data();
    }
    // Precision::Single: the coefficient set of `cell` rounded to float (the bits of at(cell), rounded).
    const float* single(const int cell[3]) {
      if (!f_.slot_.empty()) return f_.tableSingle_.data() + f_.slot_[flatCell(f_.lattice_, cell)] * f_.setSize();
      if (!std::equal(cell, cell + 3, lastSingle_)) {
        setSingle_.resize(f_.setSize());
        f_.round(at(cell), setSingle_.data());
        std::copy(cell, cell + 3, lastSingle_);
      }
      return setSingle_.data();
    }
    std::size_t windowSize() const { return window_.size() / 3; }

   private:
    const CellFields& f_;
    int last_[3] = {-1, -1, -1};
    int lastSingle_[3] = {-1, -1, -1};
    std::vector<double> window_, set_;
    std::vector<float> setSingle_;
  };

 private:
  void compute(const int cell[3], std::vector<double>& window, double* out) const {
    gatherWindow(lattice_, tables_, cell, D_, window);
    detail::cellCoefficients(poly_, cell, window.data(), windowCounts_, out);
  }

  void round(const double* set, float* out) const {
    for (std::size_t i = 0; i < setSize(); ++i) out[i] = static_cast<float>(set[i]);
  }

  const Lattice& lattice_;
  const AxisTables& tables_;
  const Eigen::MatrixX3d& D_;
  Precision precision_;
  int K_ = -1;
  int windowCounts_[3] = {};
  detail::AxisPolynomials poly_[3];
  std::vector<std::int32_t> slot_;  // flat cell -> table row; empty: no table
  std::vector<std::size_t> flats_;
  std::vector<double> table_;
  std::vector<float> tableSingle_;  // Precision::Single: table_ rounded
};

// One thread's scratch for a tile in random point order (see runTile).
struct TileScratch {
  std::vector<double> displacement;  // 3 x kTileSize, allocated on first use
  std::vector<std::uint8_t> evaluated;
  std::vector<std::uint32_t> picked;  // the tile's blocks to visit
};

// Asks for the cache lines of [begin, end) of a sorted per-point array.
template <class T>
void prefetchLines(const T* data, std::uint32_t begin, std::uint32_t end) {
  constexpr std::uint32_t kPerLine = 64 / sizeof(T);
  if (begin == end) return;
  for (std::uint32_t q = begin; q < end; q += kPerLine) {
    __builtin_prefetch(data + q);
    // A loop of prefetches alone has no side effect, and GCC deletes it as dead code.
    asm volatile("");
  }
  __builtin_prefetch(data + end - 1);  // the last line, when the steps from an unaligned begin missed it
}

// What the kernels read of a block in sorted order: its parameters (u, v, w; or the kept weights
// of a drag's control point, detail::weightedBlock) and its point order. Only the block's first
// points: the hardware prefetcher follows a long block once it has started (points in a mesh's
// spatial order make blocks of hundreds of points, where asking for all of them cost time).
void prefetchBlock(const detail::KernelInput& in, const Embedding::Block& block, const double* weights = nullptr) {
  constexpr std::uint32_t kHead = 64;
  const std::uint32_t end = std::min(block.end, block.begin + kHead);
  if (weights) {
    prefetchLines(weights, block.begin, end);
  } else {
    prefetchLines(in.u, block.begin, end);
    prefetchLines(in.v, block.begin, end);
    prefetchLines(in.w, block.begin, end);
  }
  if (in.order) prefetchLines(in.order, block.begin, end);
}

// Evaluates the blocks [first, last) of one tile that `selected` picks: run(kernelInput, block,
// blended, store) for Evaluated and Blended blocks (with the block's blend weights set),
// frozen(block) for Frozen ones. `mode` is Replace (out = Q + s d) or Accumulate (out += s d).
// A tile in random point order (sorted by cell, so its original rows are read and written in
// random order, which the hardware prefetcher cannot follow: each first touch of a line waits
// for memory) with at least an eighth of its points to run is done in two passes: the kernels
// write s d into a cache-resident scratch of the tile's rows, then detail::mergeTile streams the
// rows in original order. Fewer points (a small incremental update) are written directly.
// While a block runs, prefetch(next block) asks for what the next one will read: the blocks are
// short (~33 points of one cell per tile for 8x8x8 cubic in random point order) and, in an
// incremental update, separated by the blocks of the cells it skips, so the hardware prefetcher,
// which follows sequential streams, loses each gap and every first touch of a block's lines
// waited for memory (an exact update of 1M points on 8x8x8 after an interior control point
// moved spent 40 % of its kernel time on its parameter loads; asking one block ahead took about
// 40 % off its CPU time, docs/ffd-engine.md). Returns the number of points run.
template <class Selected, class Run, class Frozen, class Prefetch>
Eigen::Index runTile(const detail::KernelInput& in, const Embedding& embedding, std::uint32_t first, std::uint32_t last,
                     detail::Store mode, TileScratch& scratch, const Selected& selected, const Run& run,
                     const Frozen& frozen, const Prefetch& prefetch) {
  const auto& blocks = embedding.blocks();
  // The blocks to visit, listed once so that the loop below knows the next one.
  std::vector<std::uint32_t>& picked = scratch.picked;
  picked.clear();
  Eigen::Index work = 0;
  for (std::uint32_t bi = first; bi < last; ++bi) {
    const Embedding::Block& block = blocks[bi];
    if (!selected(block)) continue;
    picked.push_back(bi);
    if (block.kind != Embedding::BlockKind::Frozen) work += block.end - block.begin;
  }
  if (picked.empty()) return 0;
  detail::KernelInput local = in;
  const std::uint32_t begin = blocks[first].begin;
  const std::uint32_t end = blocks[last - 1].end;
  const bool twoPass = in.order != nullptr && 8 * work >= end - begin;
  if (twoPass) {
    if (scratch.displacement.empty()) {
      scratch.displacement.resize(3 * Embedding::kTileSize);
      scratch.evaluated.resize(Embedding::kTileSize);
    }
    double* s = scratch.displacement.data();
    local.ox = s;
    local.oy = s + Embedding::kTileSize;
    local.oz = s + 2 * Embedding::kTileSize;
    local.outOffset = begin;
    local.evaluated = scratch.evaluated.data();
    std::fill_n(scratch.evaluated.data(), end - begin, std::uint8_t(0));
  }
  for (std::size_t i = 0; i < picked.size(); ++i) {
    const Embedding::Block& block = blocks[picked[i]];
    if (block.kind == Embedding::BlockKind::Frozen) {
      frozen(block);
      continue;
    }
    if (i + 1 < picked.size()) prefetch(blocks[picked[i + 1]]);
    const bool blended = block.kind == Embedding::BlockKind::Blended;
    if (blended) {
      local.blend = embedding.blendWeight().data() + block.blendOffset;
      local.blendBegin = block.begin;
    }
    run(local, block, blended, twoPass ? detail::Store::Displacement : mode);
  }
  if (twoPass) detail::mergeTile(in, begin, end, local.ox, local.oy, local.oz, scratch.evaluated.data(), mode);
  return work;
}

// Precision::Single runs the float kernel on blocks of at least this many points; shorter ones
// (many-cell lattices in random point order: ~33 points per cell and tile for 8x8x8 cubic) were
// measured slower in float than in double (8x8x8, 10^6 points: 6.6 against 6.3 ms) and keep the
// double kernel. Fixed per block, so an exact update still gives the bits of a deform().
constexpr std::uint32_t kSingleBlockPoints = 64;

// One block through the kernel that matches the fields.
void runBlock(const detail::KernelInput& in, CellFields::Reader& reader, const CellFields& fields, const int cell[3],
              std::uint32_t begin, std::uint32_t end, bool blended, detail::Store mode) {
  if (fields.single() && end - begin >= kSingleBlockPoints)
    return detail::powerBlockSingle(in, cell, begin, end, blended, reader.single(cell), mode);
  const double* data = reader.at(cell);
  if (fields.power()) {
    detail::powerBlock(in, cell, begin, end, blended, data, mode);
  } else {
    const std::size_t size = reader.windowSize();
    detail::denseBlock(in, cell, begin, end, blended, data, data + size, data + 2 * size, mode);
  }
}

}  // namespace

Deformer::Deformer(Embedding embedding) : embedding_(std::move(embedding)) {}

const Eigen::MatrixX3d& Deformer::deform(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& input) {
  embedding_.checkLattice(lattice);
  return deformStale(lattice, input);
}

Eigen::MatrixX3d Deformer::takePoints() {
  deformed_ = false;
  denominatorsValid_ = false;
  lastControl_.resize(0, 3);
  return std::move(output_);
}

const Eigen::MatrixX3d& Deformer::deformStale(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& input) {
  if (lattice.counts() != embedding_.latticeCounts()) embedding_.checkLattice(lattice);  // throws with the details
  const Eigen::Index n = embedding_.pointCount();
  if (input.rows() != n) {
    throw LatticeError("Deformer::deform: expected " + std::to_string(n) + " x 3 input points (the embedded ones), got " +
                       std::to_string(input.rows()) + " x 3");
  }
  if (output_.rows() != n) {
    output_.resize(n, 3);
    adviseHugePages(output_);
  }
  if (lattice.isRational()) {
    evaluateRational(lattice, &input, nullptr);
  } else {
    evaluateBlocks(lattice, input, nullptr);
    denominatorsValid_ = false;
  }
  remember(lattice);
  deformed_ = true;
  stats_ = DeformStats{true, 0, n};
  return output_;
}

void Deformer::remember(const Lattice& lattice) {
  lastControl_ = lattice.controlPoints();
  lastWeights_ = lattice.weights();
  lastRational_ = lattice.isRational();
}

std::vector<char> Deformer::touchedCells(const Lattice& lattice, Eigen::Index& changed) const {
  const Eigen::MatrixX3d& P = lattice.controlPoints();
  const Eigen::VectorXd weights = lattice.weights();
  int np[3], cells[3];
  for (int a = 0; a < 3; ++a) {
    np[a] = lattice.axis(a).degree() + 1;
    cells[a] = lattice.axis(a).cellCount();
  }
  std::vector<std::vector<int>> cellsOf[3];  // cellsOf[a][i]: cells whose window holds index i on axis a
  for (int a = 0; a < 3; ++a) {
    cellsOf[a].resize(lattice.counts()[a]);
    for (int c = 0; c < cells[a]; ++c)
      for (int r = 0; r < np[a]; ++r) cellsOf[a][lattice.axis(a).controlIndex(c, r)].push_back(c);
  }
  std::vector<char> touched(static_cast<std::size_t>(cells[0]) * cells[1] * cells[2], 0);
  changed = 0;
  for (Eigen::Index f = 0; f < P.rows(); ++f) {
    if (P.row(f) == lastControl_.row(f) && weights[f] == lastWeights_[f]) continue;
    ++changed;
    const Eigen::Vector3i g = lattice.gridIndex(f);
    for (int cw : cellsOf[2][g[2]])
      for (int cv : cellsOf[1][g[1]])
        for (int cu : cellsOf[0][g[0]]) touched[cu + cells[0] * (cv + static_cast<std::size_t>(cells[1]) * cw)] = 1;
  }
  return touched;
}

Eigen::Index Deformer::evaluateBlocks(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& input,
                                      const std::vector<char>* cellFilter) {
  // World displacement of every control point: F.linear * (P - Pbar).
  const Eigen::MatrixX3d D = (lattice.controlPoints() - lattice.restPoints()) * lattice.frame().linear().transpose();
  const AxisTables tables = makeTables(lattice);
  CellFields fields(lattice, tables, D, precision_);
  const detail::AxisPolynomials* const poly[3] = {fields.polynomials(0), fields.polynomials(1), fields.polynomials(2)};
  detail::KernelInput in = detail::kernelInput(lattice, embedding_, tables.span, poly, output_);
  in.qx = input.col(0).data();
  in.qy = input.col(1).data();
  in.qz = input.col(2).data();
  const auto& blocks = embedding_.blocks();
  const auto& tiles = embedding_.tileBlocks();
  const std::int64_t tileCount = static_cast<std::int64_t>(tiles.size()) - 1;
  auto inFilter = [&](const Embedding::Block& block) { return !cellFilter || (*cellFilter)[block.cell]; };
  // The points to evaluate and the cells they lie in.
  Eigen::Index work = 0;
  {
    std::vector<char> used(static_cast<std::size_t>(cellTotalOf(lattice)), 0);
    std::vector<std::size_t> flats;
    for (const Embedding::Block& block : blocks) {
      if (!inFilter(block)) continue;
      work += block.end - block.begin;
      if (block.kind == Embedding::BlockKind::Frozen) continue;
      const std::size_t flat = block.cell;
      if (!used[flat]) flats.push_back(flat);
      used[flat] = 1;
    }
    fields.plan(std::move(flats), work);
  }
  // Few points to evaluate (a small incremental update): stay on this thread; waking OpenMP
  // workers costs more, and on a busy machine their spinning slows everything else down.
  const bool parallel = parallel_ && work >= kParallelPoints;
  Eigen::Index evaluated = 0;
#pragma omp parallel if (parallel) reduction(+ : evaluated)
  {
    fields.fillTable();
    CellFields::Reader reader(fields);
    TileScratch scratch;
    auto run = [&](const detail::KernelInput& local, const Embedding::Block& block, bool blended, detail::Store mode) {
      runBlock(local, reader, fields, embedding_.cellOf(block).data(), block.begin, block.end, blended, mode);
    };
    // Identity outside, Failed, beyond Falloff: the input unchanged.
    auto frozen = [&](const Embedding::Block& block) {
      for (std::uint32_t q = block.begin; q < block.end; ++q) {
        const Eigen::Index p = in.order ? in.order[q] : q;
        output_.row(p) = input.row(p);
      }
    };
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t t = 0; t < tileCount; ++t) {
      evaluated += runTile(in, embedding_, tiles[t], tiles[t + 1], detail::Store::Replace, scratch, inFilter, run, frozen,
                           [&](const Embedding::Block& block) { prefetchBlock(in, block); });
    }
  }
  return evaluated;
}

const Eigen::MatrixX3d& Deformer::update(const Lattice& lattice, const Eigen::Ref<const Eigen::MatrixX3d>& input) {
  embedding_.checkLattice(lattice);
  if (!deformed_) throw LatticeError("Deformer::update: call deform() once before incremental updates");
  if (input.rows() != embedding_.pointCount()) {
    throw LatticeError("Deformer::update: expected " + std::to_string(embedding_.pointCount()) +
                       " x 3 input points (the embedded ones), got " + std::to_string(input.rows()) + " x 3");
  }
  Eigen::Index changed = 0;
  const std::vector<char> touched = touchedCells(lattice, changed);
  stats_ = DeformStats{false, changed, 0};
  if (changed == 0) return output_;
  const bool rational = lattice.isRational();
  // A switch between the rational and the polynomial path (or rational sums not kept) evaluates
  // every point, so that the output is that of a deform() on either path.
  const bool all = rational != lastRational_ || (rational && !denominatorsValid_);
  if (rational) {
    stats_.evaluatedPoints = evaluateRational(lattice, &input, all ? nullptr : &touched);
  } else {
    stats_.evaluatedPoints = evaluateBlocks(lattice, input, all ? nullptr : &touched);
    denominatorsValid_ = false;
  }
  remember(lattice);
  return output_;
}

const Eigen::MatrixX3d& Deformer::update(const Lattice& lattice) {
  embedding_.checkLattice(lattice);
  if (!deformed_) throw LatticeError("Deformer::update: call deform() once before incremental updates");
  if (lattice.isRational() || lastRational_) return updateRational(lattice);
  const Eigen::MatrixX3d& P = lattice.controlPoints();
  std::vector<Eigen::Index> changed;
  for (Eigen::Index f = 0; f < P.rows(); ++f) {
    if (P.row(f) != lastControl_.row(f)) changed.push_back(f);
  }
  stats_ = DeformStats{false, static_cast<Eigen::Index>(changed.size()), 0};
  if (changed.empty()) return output_;
  const Eigen::MatrixX3d D = (P - lastControl_) * lattice.frame().linear().transpose();

  // For every cell touched by a changed control point: the list of (window position, change),
  // or, when most of its window changed, the dense window of changes.
  const AxisTables tables = makeTables(lattice);
  int np[3], cells[3];
  for (int a = 0; a < 3; ++a) {
    np[a] = lattice.axis(a).degree() + 1;
    cells[a] = lattice.axis(a).cellCount();
  }
  // cellsOf[a][i] = (cell, r) pairs whose window holds control index i on axis a.
  std::vector<std::vector<std::pair<int, int>>> cellsOf[3];
  for (int a = 0; a < 3; ++a) {
    cellsOf[a].resize(lattice.counts()[a]);
    for (int c = 0; c < cells[a]; ++c)
      for (int r = 0; r < np[a]; ++r) cellsOf[a][tables.window[a][c * np[a] + r]].push_back({c, r});
  }
  const int windowSize = np[0] * np[1] * np[2];
  const std::size_t cellTotal = static_cast<std::size_t>(cells[0]) * cells[1] * cells[2];
  std::vector<std::vector<detail::SparseTerm>> terms(cellTotal);
  for (Eigen::Index f : changed) {
    const Eigen::Vector3i g = lattice.gridIndex(f);
    for (const auto& [cw, rw] : cellsOf[2][g[2]])
      for (const auto& [cv, rv] : cellsOf[1][g[1]])
        for (const auto& [cu, ru] : cellsOf[0][g[0]]) {
          terms[cu + cells[0] * (cv + static_cast<std::size_t>(cells[1]) * cw)].push_back(
              {ru, rv, rw, D(f, 0), D(f, 1), D(f, 2)});
        }
  }
  CellFields fields(lattice, tables, D, precision_);
  // Most of a cell's window moved: the dense evaluation is cheaper than one term per point
  // (a term costs about 1/16 of a dense power-form point, 1/3 of a dense Cox-de Boor one).
  std::vector<char> dense(cellTotal, 0);
  std::vector<std::size_t> denseCells;
  for (std::size_t cell = 0; cell < cellTotal; ++cell) {
    if ((fields.power() ? 16 : 3) * terms[cell].size() > static_cast<std::size_t>(windowSize)) {
      dense[cell] = 1;
      denseCells.push_back(cell);
    }
  }

  // One control point moved and every cell it touches takes one sparse term (a drag): its weights
  // at the points are kept by this step, or were kept by the last step of the same control point
  // and are read instead of evaluating the basis (the same bits).
  enum class Weights { None, Keep, Read } stepWeights = Weights::None;
  if (changed.size() == 1 && denseCells.empty() &&
      std::all_of(terms.begin(), terms.end(), [](const auto& t) { return t.size() <= 1; })) {
    if (stepWeightsControl_ == changed.front() && stepWeightsRest_ == lattice.restRevision() &&
        stepWeights_.size() == embedding_.pointCount()) {
      stepWeights = Weights::Read;
    } else {
      stepWeights = Weights::Keep;
      stepWeightsControl_ = -1;  // valid once every touched point is written
      if (stepWeights_.size() != embedding_.pointCount()) {
        stepWeights_.resize(embedding_.pointCount());
        adviseHugePages(stepWeights_);
      }
    }
  }
  const detail::AxisPolynomials* const poly[3] = {fields.polynomials(0), fields.polynomials(1), fields.polynomials(2)};
  detail::KernelInput in = detail::kernelInput(lattice, embedding_, tables.span, poly, output_);
  const auto& blocks = embedding_.blocks();
  const auto& tiles = embedding_.tileBlocks();
  const std::int64_t tileCount = static_cast<std::int64_t>(tiles.size()) - 1;
  Eigen::Index evaluated = 0;
  Eigen::Index work = 0;
  for (const Embedding::Block& block : blocks) {
    if (block.kind != Embedding::BlockKind::Frozen && !terms[block.cell].empty())
      work += block.end - block.begin;
  }
  fields.plan(std::move(denseCells), work);
  auto touched = [&](const Embedding::Block& block) {
    return block.kind != Embedding::BlockKind::Frozen && !terms[block.cell].empty();
  };
  const bool parallel = parallel_ && work >= kParallelPoints;
#pragma omp parallel if (parallel) reduction(+ : evaluated)
  {
    fields.fillTable();
    CellFields::Reader reader(fields);
    TileScratch scratch;
    auto run = [&](const detail::KernelInput& local, const Embedding::Block& block, bool blended, detail::Store mode) {
      const std::size_t cell = block.cell;
      if (dense[cell]) {
        runBlock(local, reader, fields, embedding_.cellOf(block).data(), block.begin, block.end, blended, mode);
      } else if (stepWeights == Weights::Read) {
        detail::weightedBlock(local, block.begin, block.end, blended, stepWeights_.data(), terms[cell].front(), mode);
      } else if (stepWeights == Weights::Keep) {
        detail::sparseBlockKeepingWeights(local, embedding_.cellOf(block).data(), block.begin, block.end, blended,
                                          terms[cell].front(), mode, stepWeights_.data());
      } else {
        detail::sparseBlock(local, embedding_.cellOf(block).data(), block.begin, block.end, blended, terms[cell].data(),
                            static_cast<int>(terms[cell].size()), mode);
      }
    };
    // What the next block's kernel reads: a step that reads the kept weights (weightedBlock)
    // reads them in place of the parameters (prefetching the parameters there as well made the
    // delta update of the benchmarks 13 % slower).
    auto prefetch = [&](const Embedding::Block& block) {
      const bool weightsOnly = stepWeights == Weights::Read && !dense[block.cell];
      prefetchBlock(in, block, weightsOnly ? stepWeights_.data() : nullptr);
    };
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t t = 0; t < tileCount; ++t) {
      evaluated += runTile(in, embedding_, tiles[t], tiles[t + 1], detail::Store::Accumulate, scratch, touched, run,
                           [](const Embedding::Block&) {}, prefetch);
    }
  }
  stats_.evaluatedPoints = evaluated;
  stats_.weightsReused = stepWeights == Weights::Read;
  if (stepWeights == Weights::Keep) {
    stepWeightsControl_ = changed.front();
    stepWeightsRest_ = lattice.restRevision();
  }
  remember(lattice);
  denominatorsValid_ = false;
  return output_;
}

bool Deformer::keptControlWeights(const Lattice& lattice, Eigen::Index flat, Eigen::VectorXd& weights) const {
  const Eigen::Index n = embedding_.pointCount();
  if (stepWeightsControl_ < 0 || stepWeightsControl_ != flat || stepWeightsRest_ != lattice.restRevision() ||
      lattice.isRational() || lattice.counts() != embedding_.latticeCounts() || stepWeights_.size() != n)
    return false;
  // The cells whose window holds the control point, per axis: those update(lattice) gave its term
  // and whose points' weights it kept (a wrapped window gives two terms and keeps none).
  const Eigen::Vector3i g = lattice.gridIndex(flat);
  std::vector<char> holds[3];
  for (int a = 0; a < 3; ++a) {
    const AxisSpline& axis = lattice.axis(a);
    holds[a].assign(static_cast<std::size_t>(axis.cellCount()), 0);
    for (int c = 0; c < axis.cellCount(); ++c)
      for (int r = 0; r <= axis.degree(); ++r)
        if (axis.controlIndex(c, r) == g[a]) holds[a][static_cast<std::size_t>(c)] = 1;
  }
  if (weights.size() != n) weights.resize(n);
  const auto& blocks = embedding_.blocks();
  const auto& tiles = embedding_.tileBlocks();
  const std::uint32_t* order = embedding_.order().empty() ? nullptr : embedding_.order().data();
  const double* kept = stepWeights_.data();
  double* out = weights.data();
  const std::int64_t tileCount = static_cast<std::int64_t>(tiles.size()) - 1;
#pragma omp parallel for schedule(static) if (parallel_ && n >= kParallelPoints)
  for (std::int64_t t = 0; t < tileCount; ++t) {
    for (std::uint32_t bi = tiles[t]; bi < tiles[t + 1]; ++bi) {
      const Embedding::Block& block = blocks[bi];
      const std::array<int, 3> cell = embedding_.cellOf(block);
      const bool inWindow = block.kind != Embedding::BlockKind::Frozen && holds[0][std::size_t(cell[0])] &&
                            holds[1][std::size_t(cell[1])] && holds[2][std::size_t(cell[2])];
      const double* blend = block.kind == Embedding::BlockKind::Blended
                                ? embedding_.blendWeight().data() + block.blendOffset - block.begin
                                : nullptr;
      for (std::uint32_t q = block.begin; q < block.end; ++q) {
        // s * B as controlPointWeights multiplies them (s = 1 needs no product).
        const double w = !inWindow ? 0.0 : blend ? blend[q] * kept[q] : kept[q];
        out[order ? order[q] : q] = w;
      }
    }
  }
  return true;
}

}  // namespace ffdkit::ffd
