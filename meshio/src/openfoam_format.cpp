// The files of an OpenFOAM polyMesh from their bytes: the FoamFile header, then one list
// (`N (...)`) in ASCII or binary (OpenFOAM User Guide, sec. 4.2; binary lists are `N(` followed
// by N raw items and `)`). Every list size is checked against the bytes left and charged to the
// budget before anything is allocated.
#include <algorithm>
#include <bit>
#include <climits>
#include <cstring>

#include <zlib.h>

#include "ffdkit/meshio/openfoam.h"
#include "foam_scanner.h"
#include "formats.h"
#include "mapped_file.h"
#include "openfoam_files.h"
#include "parse_support.h"

namespace ffdkit::meshio {

namespace {

using detail::FoamScanner;
using detail::Where;

constexpr std::int64_t kMaxLabel32 = INT32_MAX;

// `arch "LSB;label=32;scalar=64"`.
void parseArch(std::string_view arch, FoamFileLayout& layout, const FoamScanner& s) {
  std::size_t start = 0;
  while (start <= arch.size()) {
    std::size_t end = arch.find(';', start);
    if (end == std::string_view::npos) end = arch.size();
    const std::string_view part = arch.substr(start, end - start);
    if (part == "LSB") layout.bigEndian = false;
    else if (part == "MSB") layout.bigEndian = true;
    else if (part == "label=32") layout.labelBytes = 4;
    else if (part == "label=64") layout.labelBytes = 8;
    else if (part == "scalar=32") layout.scalarBytes = 4;
    else if (part == "scalar=64") layout.scalarBytes = 8;
    else if (!part.empty()) s.fail("FoamFile: arch \"" + std::string(arch) + "\": '" + std::string(part) + "' is not known (LSB or MSB, label=32|64, scalar=32|64)");
    start = end + 1;
  }
}

// Skips a dictionary entry's value up to and including its ';' (words, strings, nested lists).
void skipValue(FoamScanner& s, const Where& where) {
  int depth = 0;
  for (;;) {
    s.skipSpace();
    const char c = s.peek();
    if (s.atEnd()) s.fail(where.text() + ": the entry has no ';'");
    if (c == ';' && depth == 0) {
      s.advance();
      return;
    }
    if (c == '(' || c == '{' || c == '[') {
      ++depth;
      s.advance();
    } else if (c == ')' || c == '}' || c == ']') {
      if (--depth < 0) s.fail(where.text() + ": unbalanced " + s.shown());
      s.advance();
    } else if (c == '"') {
      s.quoted(where);
    } else if (c == ';') {
      s.advance();
    } else if (s.word().empty()) {
      s.advance();  // a lone '/' (not a comment)
    }
  }
}

// The FoamFile header: `FoamFile { key value; ... }`. `classes`: the classes this file may have.
FoamFileLayout readHeader(FoamScanner& s, std::initializer_list<std::string_view> classes) {
  const Where header{"FoamFile"};
  if (s.word() != "FoamFile") s.fail("expected the FoamFile header, got " + s.shown());
  s.expect('{', header);
  FoamFileLayout layout;
  bool haveFormat = false;
  for (;;) {
    s.skipSpace();
    if (s.peek() == '}') {
      s.advance();
      break;
    }
    const std::string_view key = s.word();
    if (key.empty()) s.fail("FoamFile: expected a keyword or '}', got " + s.shown());
    const Where entry{"FoamFile", -1, key};
    if (key == "format") {
      const std::string_view value = s.word();
      if (value == "ascii") layout.binary = false;
      else if (value == "binary") layout.binary = true;
      else s.fail("FoamFile: format '" + std::string(value) + "' is not ascii or binary");
      s.expect(';', entry);
      haveFormat = true;
    } else if (key == "class") {
      layout.className = std::string(s.word());
      s.expect(';', entry);
    } else if (key == "arch") {
      parseArch(s.quoted(entry), layout, s);
      s.expect(';', entry);
    } else {
      skipValue(s, entry);
    }
  }
  if (!haveFormat) s.fail("FoamFile: no 'format' entry");
  if (std::find(classes.begin(), classes.end(), layout.className) == classes.end()) {
    std::string known;
    for (auto c : classes) known.append(known.empty() ? "" : ", ").append(c);
    s.fail("FoamFile: class '" + layout.className + "' is not what this file holds (" + known + ")");
  }
  return layout;
}

// A list's size `N` and its opening '(' (for a binary list, the data start right after it).
// `minItemBytes`: the fewest bytes an item takes, to check N against the bytes left.
std::int64_t openList(FoamScanner& s, const char* what, std::int64_t maxSize, std::uint64_t minItemBytes) {
  const std::int64_t n = s.label(Where{what, -1, "list size"}, 0, maxSize);
  const int sizeLine = s.line();
  s.skipSpace();
  if (s.peek() == '{')
    s.failAt(sizeLine, std::string(what) + ": a uniform list N{value} is not supported here (expected N followed by '(')");
  if (minItemBytes > 0 && std::uint64_t(n) > s.bytesLeft() / minItemBytes)
    s.failAt(sizeLine, std::string(what) + ": a list of " + std::to_string(n) + " needs at least " +
           std::to_string(std::uint64_t(n) * minItemBytes) + " bytes, the file has " + std::to_string(s.bytesLeft()) +
           " left (truncated, or the size is wrong)");
  s.expect('(', Where{what, -1, "list"});
  return n;
}

// The ')' that closes a list; for a binary list, right after its data.
void closeList(FoamScanner& s, const char* what, bool binary, std::int64_t n) {
  if (binary) {
    if (s.peek() != ')')
      s.fail(std::string(what) + ": expected ')' right after the " + std::to_string(n) + " binary items, got " + s.shown() +
             " (the list size is wrong, or the list is not binary as the header's 'format binary' says)");
    s.advance();
  } else {
    s.expect(')', Where{what, -1, "list end"});
  }
}

// Nothing but space and comments after the last list.
void expectEnd(FoamScanner& s) {
  s.skipSpace();
  if (!s.atEnd()) s.fail("unexpected " + s.shown() + " after the list");
}

// Raw binary items: the bytes for `count` items of `itemBytes` must be there.
void needBinary(const FoamScanner& s, const char* what, std::int64_t count, std::uint64_t itemBytes) {
  const std::uint64_t need = std::uint64_t(count) * itemBytes;
  if (need > s.bytesLeft())
    s.fail(std::string("truncated: ") + what + ": " + std::to_string(count) + " binary items need " + std::to_string(need) +
           " bytes at offset " + std::to_string(s.pos()) + ", the file has " + std::to_string(s.bytesLeft()) + " left");
}

// Whether the n native 32-bit labels at `at` all lie in [lo, hi]: one pass without a branch per
// label (the compiler vectorises it).
bool allInRange(const char* at, std::size_t n, std::int32_t lo, std::int32_t hi) {
  constexpr std::size_t kRun = 4096;
  // label - lo as unsigned: above hi - lo exactly when the label is outside [lo, hi].
  const std::uint32_t span = std::uint32_t(hi) - std::uint32_t(lo);
  for (std::size_t first = 0; first < n; first += kRun) {
    const std::size_t count = std::min(kRun, n - first);
    const char* run = at + first * sizeof(std::int32_t);
    std::uint32_t outside = 0;
    for (std::size_t i = 0; i < count; ++i) {
      std::uint32_t label;
      std::memcpy(&label, run + i * sizeof label, sizeof label);  // any alignment (a list read in place)
      outside |= std::uint32_t(label - std::uint32_t(lo) > span);
    }
    if (outside != 0) return false;
  }
  return true;
}

// allInRange on every core, in runs of 1 Mi labels (a list read in place is checked where it lies).
bool allInRangeOnEveryCore(const char* at, std::size_t n, std::int32_t lo, std::int32_t hi) {
  constexpr std::size_t kRun = std::size_t(1) << 20;
  const std::int64_t runs = std::int64_t((n + kRun - 1) / kRun);
  bool inRange = true;
#pragma omp parallel for schedule(dynamic, 8) reduction(&& : inRange) if (runs > 4)
  for (std::int64_t r = 0; r < runs; ++r) {
    const std::size_t first = std::size_t(r) * kRun;
    inRange = allInRange(at + first * sizeof(std::int32_t), std::min(kRun, n - first), lo, hi) && inRange;
  }
  return inRange;
}

// Appends the n native 32-bit labels at `at` to `out` (empty, with room for them reserved) a run
// at a time, each run checked in `out` and its source bytes given back (releaseParsedBytes: a
// mapped file's pages leave the process as they are copied). A run is small enough to stay in
// the cache between its zero fill (resize), its copy and its check, so the fresh memory is
// written from the cache. Whether every label lies in [lo, hi].
bool appendLabelsInRange(const char* at, std::size_t n, std::int32_t lo, std::int32_t hi, std::vector<std::int32_t>& out) {
  constexpr std::size_t kRun = std::size_t(1) << 16;  // 256 KiB of labels
  constexpr std::size_t kRelease = std::size_t(1) << 21;  // madvise 8 MiB of the file at a time
  std::size_t released = 0;
  for (std::size_t first = 0; first < n; first += kRun) {
    const std::size_t count = std::min(kRun, n - first);
    out.resize(first + count);  // within the reserved capacity: no reallocation
    std::memcpy(out.data() + first, at + first * sizeof(std::int32_t), count * sizeof(std::int32_t));
    if (!allInRange(reinterpret_cast<const char*>(out.data() + first), count, lo, hi)) return false;
    if (first + count - released >= kRelease || first + count == n) {
      detail::releaseParsedBytes(at + released * sizeof(std::int32_t), at + (first + count) * sizeof(std::int32_t));
      released = first + count;
    }
  }
  return true;
}

template <class T>
T loadBinary(const char* at, bool bigEndian) {
  char raw[sizeof(T)];
  std::memcpy(raw, at, sizeof(T));
  if (bigEndian != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
  T value;
  std::memcpy(&value, raw, sizeof(T));
  return value;
}

std::int64_t binaryLabel(const char* at, const FoamFileLayout& layout) {
  return layout.labelBytes == 4 ? std::int64_t(loadBinary<std::int32_t>(at, layout.bigEndian))
                                : loadBinary<std::int64_t>(at, layout.bigEndian);
}

// One label list (`N (l l l ...)` or binary) into `out`, each label in [lo, hi]; `what` names
// an item ("owner" -> "owner 12"). Charged before it is allocated (also when it is read in
// place: the budget's rule does not depend on how the file is read). With a `keeper`, a binary
// list in the machine's own layout is read where it lies in the scanner's bytes (which `keeper`
// keeps readable), once every label is checked; others are copied into memory.
void readLabelList(FoamScanner& s, const FoamFileLayout& layout, const char* what, std::int64_t lo, std::int64_t hi,
                   ReadBudget& budget, LabelList& out, const std::shared_ptr<const void>& keeper,
                   std::int64_t maxSize = kMaxLabel32) {
  const std::int64_t n = openList(s, what, maxSize, layout.binary ? std::uint64_t(layout.labelBytes) : 2);
  budget.chargeBytes(std::uint64_t(n), sizeof(std::int32_t), std::string(what) + " labels");
  std::vector<std::int32_t> labels;
  if (layout.binary) {
    needBinary(s, what, n, std::uint64_t(layout.labelBytes));
    const char* at = s.text().data() + s.pos();
    const bool native = layout.labelBytes == 4 && layout.bigEndian == (std::endian::native == std::endian::big);
    const std::int32_t lo32 = std::int32_t(lo), hi32 = std::int32_t(std::min<std::int64_t>(hi, kMaxLabel32));
    if (native && keeper != nullptr && allInRangeOnEveryCore(at, std::size_t(n), lo32, hi32)) {
      out = LabelList::inPlace(keeper, at, std::size_t(n));
      s.advance(std::size_t(n) * sizeof(std::int32_t));
      closeList(s, what, layout.binary, n);
      return;
    }
    labels.reserve(std::size_t(n));
    if (native && keeper == nullptr && appendLabelsInRange(at, std::size_t(n), lo32, hi32, labels)) {
      // The file's own layout: one copy; the item-by-item loop below only finds the bad label.
      out = std::move(labels);
      s.advance(std::size_t(n) * sizeof(std::int32_t));
      closeList(s, what, layout.binary, n);
      return;
    }
    labels.resize(std::size_t(n));
    for (std::int64_t i = 0; i < n; ++i, at += layout.labelBytes) {
      const std::int64_t value = binaryLabel(at, layout);
      if (value < lo || value > hi)
        s.fail(Where{what, i}.text() + " (binary, offset " + std::to_string(s.pos() + std::size_t(i) * std::size_t(layout.labelBytes)) +
               "): " + std::to_string(value) + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
      labels[std::size_t(i)] = std::int32_t(value);
    }
    s.advance(std::size_t(n) * std::size_t(layout.labelBytes));
  } else {
    labels.resize(std::size_t(n));
    for (std::int64_t i = 0; i < n; ++i) labels[std::size_t(i)] = std::int32_t(s.label(Where{what, i}, lo, hi));
  }
  out = std::move(labels);
  closeList(s, what, layout.binary, n);
}

// Whether some face of the offsets at `starts` (n + 1 of them) has fewer than 3 points: one
// branch-free pass on every core.
bool anyShortFace(const char* starts, std::size_t n) {
  constexpr std::size_t kRun = std::size_t(1) << 20;
  const std::int64_t runs = std::int64_t((n + kRun - 1) / kRun);
  bool short_ = false;
#pragma omp parallel for schedule(dynamic, 8) reduction(|| : short_) if (runs > 4)
  for (std::int64_t r = 0; r < runs; ++r) {
    const std::size_t first = std::size_t(r) * kRun, last = std::min(n, first + kRun);
    bool any = false;
    for (std::size_t f = first; f < last; ++f) {
      std::int32_t pair[2];
      std::memcpy(pair, starts + f * sizeof(std::int32_t), sizeof pair);
      any |= pair[1] - pair[0] < 3;
    }
    short_ = short_ || any;
  }
  return short_;
}

}  // namespace

Eigen::MatrixX3d readFoamPoints(std::string_view bytes, const std::string& source, ReadBudget& budget,
                                FoamPointsFile* file) {
  FoamScanner s(bytes, source);
  const FoamFileLayout layout = readHeader(s, {"vectorField"});
  const std::uint64_t itemBytes = layout.binary ? 3 * std::uint64_t(layout.scalarBytes) : 7;  // "(0 0 0)"
  const std::int64_t n = openList(s, "point", INT_MAX, itemBytes);
  const std::size_t listBegin = s.pos();
  const int listLine = s.line();
  budget.chargePoints(std::uint64_t(n), "points: a list of " + std::to_string(n));
  Eigen::MatrixX3d points(Eigen::Index(n), 3);
  detail::adviseHugePages(points);
  if (layout.binary) {
    needBinary(s, "point", n, itemBytes);
    const char* at = bytes.data() + s.pos();
    bool fast = layout.scalarBytes == 8 && layout.bigEndian == (std::endian::native == std::endian::big);
    if (fast) {
      // The file's own doubles: copied to the columns in one pass; a non-finite value (all exponent
      // bits set) makes the item-by-item loop below run to name it.
      double* x = points.col(0).data();
      double* y = points.col(1).data();
      double* z = points.col(2).data();
      std::uint64_t special = 0;
      constexpr std::uint64_t kExponent = 0x7ff0000000000000ULL;
      // Runs of 6 MiB of the file, one per core at a time; the thread that read the file gives
      // the runs' pages back once they are copied (releaseParsedBytes knows the mapping there).
      constexpr Eigen::Index kRun = Eigen::Index(1) << 18;
      constexpr Eigen::Index kRound = 2 * kRun;
#pragma omp parallel if (n > kRound)
      for (Eigen::Index round = 0; round < n; round += kRound) {
#pragma omp for schedule(static, 1) reduction(| : special)
        for (Eigen::Index first = round; first < std::min<Eigen::Index>(n, round + kRound); first += kRun) {
          const Eigen::Index last = std::min<Eigen::Index>(n, first + kRun);
          for (Eigen::Index i = first; i < last; ++i) {
            std::uint64_t raw[3];
            std::memcpy(raw, at + std::size_t(i) * 24, 24);
            special |= std::uint64_t((raw[0] & kExponent) == kExponent) |
                       std::uint64_t((raw[1] & kExponent) == kExponent) | std::uint64_t((raw[2] & kExponent) == kExponent);
            x[i] = std::bit_cast<double>(raw[0]);
            y[i] = std::bit_cast<double>(raw[1]);
            z[i] = std::bit_cast<double>(raw[2]);
          }
        }
#pragma omp master
        detail::releaseParsedBytes(at + std::size_t(round) * 24, at + std::size_t(std::min<Eigen::Index>(n, round + kRound)) * 24);
      }
      fast = special == 0;
    }
    for (Eigen::Index i = 0; !fast && i < n; ++i)
      for (int c = 0; c < 3; ++c, at += layout.scalarBytes) {
        const double value = layout.scalarBytes == 8 ? loadBinary<double>(at, layout.bigEndian)
                                                     : double(loadBinary<float>(at, layout.bigEndian));
        if (!std::isfinite(value))
          s.fail(Where{"point", i}.text() + " (binary, offset " + std::to_string(std::size_t(at - bytes.data())) +
                 "): non-finite coordinate");
        points(i, c) = value;
      }
    s.advance(std::size_t(n) * itemBytes);
  } else {
    for (Eigen::Index i = 0; i < n; ++i) {
      const Where where{"point", i};
      s.expect('(', where);
      for (int c = 0; c < 3; ++c) points(i, c) = s.scalar(where);
      s.expect(')', where);
    }
  }
  const std::size_t listEnd = s.pos();
  closeList(s, "point", layout.binary, n);
  expectEnd(s);
  if (file != nullptr) {
    file->layout = layout;
    file->listBegin = listBegin;
    file->listEnd = listEnd;
    file->listLine = listLine;
  }
  return points;
}

namespace detail {

void readFoamFacesInPlace(std::string_view bytes, const std::string& source, std::int64_t pointCount, ReadBudget& budget,
                          PolyMeshCells& cells, const std::shared_ptr<const void>& keeper) {
  FoamScanner s(bytes, source);
  const FoamFileLayout layout = readHeader(s, {"faceList", "faceCompactList"});
  const std::int64_t lastPoint = pointCount - 1;
  if (layout.className == "faceCompactList") {
    // Two lists: the #F + 1 offsets of each face's points, then the points.
    const LabelList& starts = cells.faceStarts;
    readLabelList(s, layout, "face offset", 0, kMaxLabel32, budget, cells.faceStarts, keeper, kMaxLabel32);
    if (starts.empty()) s.fail("face offset: the list is empty (it needs the number of faces + 1 offsets)");
    if (starts.front() != 0) s.fail("face offset 0: " + std::to_string(starts.front()) + ", expected 0");
    // One branch-free pass; the loop below names the first short face.
    const bool short_ = anyShortFace(starts.bytes(), starts.size() - 1);
    for (std::size_t f = 0; short_ && f + 1 < starts.size(); ++f)
      if (starts[f + 1] - starts[f] < 3)
        s.fail(Where{"face", std::int64_t(f)}.text() + ": " + std::to_string(starts[f + 1] - starts[f]) +
               " points (offsets " + std::to_string(starts[f]) + ".." + std::to_string(starts[f + 1]) +
               "); a face needs at least 3 and the offsets must increase");
    readLabelList(s, layout, "face point", 0, lastPoint, budget, cells.faceVertices, keeper);
    if (std::int64_t(cells.faceVertices.size()) != cells.faceStarts.back())
      s.fail("faces: the offsets end at " + std::to_string(cells.faceStarts.back()) + " but the point list has " +
             std::to_string(cells.faceVertices.size()) + " entries");
    expectEnd(s);
    return;
  }
  if (layout.binary) s.fail("faces: a binary faceList is not supported (OpenFOAM writes binary faces as faceCompactList)");
  const std::int64_t n = openList(s, "face", kMaxLabel32, 8);  // "3(0 0 0)"
  budget.chargeBytes(std::uint64_t(n) + 1, sizeof(std::int32_t), "faces: offsets");
  std::vector<std::int32_t> starts(std::size_t(n) + 1);
  std::vector<std::int32_t> vertices;
  starts[0] = 0;
  // At most one point per two bytes left: the vertex list never grows past what the file holds.
  const std::size_t most = s.bytesLeft() / 2;
  std::size_t charged = 0;
  for (std::int64_t f = 0; f < n; ++f) {
    const Where where{"face", f};
    const std::int64_t k = s.label(where, 3, std::int64_t(std::min<std::size_t>(most, kMaxLabel32)));
    if (std::int64_t(vertices.size()) + k > kMaxLabel32)
      s.fail(where.text() + ": the faces hold more than " + std::to_string(kMaxLabel32) + " points in all (more than a polyMesh of label=32 holds)");
    if (vertices.size() + std::size_t(k) > charged) {
      const std::size_t want = std::min(most, std::max<std::size_t>({64, 2 * charged, vertices.size() + std::size_t(k)}));
      budget.chargeBytes(want - charged, sizeof(std::int32_t), "faces: point indices");
      vertices.reserve(want);
      charged = want;
    }
    s.expect('(', where);
    for (std::int64_t j = 0; j < k; ++j) vertices.push_back(std::int32_t(s.label(where, 0, lastPoint)));
    s.expect(')', where);
    starts[std::size_t(f) + 1] = std::int32_t(vertices.size());
  }
  closeList(s, "face", false, n);
  expectEnd(s);
  cells.faceStarts = std::move(starts);
  cells.faceVertices = std::move(vertices);
}

LabelList readFoamLabelsInPlace(std::string_view bytes, const std::string& source, std::int64_t maxLabel, ReadBudget& budget,
                                const std::shared_ptr<const void>& keeper) {
  FoamScanner s(bytes, source);
  const FoamFileLayout layout = readHeader(s, {"labelList"});
  LabelList labels;
  readLabelList(s, layout, "label", 0, std::min(maxLabel, kMaxLabel32), budget, labels, keeper);
  expectEnd(s);
  return labels;
}

}  // namespace detail

void readFoamFaces(std::string_view bytes, const std::string& source, std::int64_t pointCount, ReadBudget& budget,
                   PolyMeshCells& cells) {
  detail::readFoamFacesInPlace(bytes, source, pointCount, budget, cells, nullptr);
}

std::vector<std::int32_t> readFoamLabels(std::string_view bytes, const std::string& source, std::int64_t maxLabel,
                                         ReadBudget& budget) {
  return std::move(detail::readFoamLabelsInPlace(bytes, source, maxLabel, budget, nullptr).held());
}

std::vector<PolyMeshPatch> readFoamBoundary(std::string_view bytes, const std::string& source,
                                            std::int64_t firstBoundaryFace, std::int64_t faceCount) {
  FoamScanner s(bytes, source);
  (void)readHeader(s, {"polyBoundaryMesh"});
  const std::int64_t n = openList(s, "patch", 1'000'000, 4);  // "a{}" and a space at least
  std::vector<PolyMeshPatch> patches;
  std::int64_t covered = 0;
  for (std::int64_t p = 0; p < n; ++p) {
    PolyMeshPatch patch;
    patch.name = std::string(s.word());
    const Where where{"patch", p, patch.name};
    if (patch.name.empty()) s.fail(where.text() + ": expected a patch name, got " + s.shown());
    s.expect('{', where);
    bool haveStart = false, haveCount = false;
    for (;;) {
      s.skipSpace();
      if (s.peek() == '}') {
        s.advance();
        break;
      }
      const std::string_view key = s.word();
      if (key.empty()) s.fail(where.text() + ": expected a keyword or '}', got " + s.shown());
      if (key == "startFace") {
        patch.startFace = s.label(Where{"patch", p, "startFace"}, firstBoundaryFace, faceCount);
        s.expect(';', where);
        haveStart = true;
      } else if (key == "nFaces") {
        patch.faceCount = s.label(Where{"patch", p, "nFaces"}, 0, faceCount);
        s.expect(';', where);
        haveCount = true;
      } else if (key == "type") {
        patch.type = std::string(s.word());
        s.expect(';', where);
      } else {
        skipValue(s, where);
      }
    }
    if (!haveStart || !haveCount) s.fail(where.text() + ": needs 'startFace' and 'nFaces'");
    if (patch.startFace + patch.faceCount > faceCount)
      s.fail(where.text() + ": faces " + std::to_string(patch.startFace) + ".." +
             std::to_string(patch.startFace + patch.faceCount - 1) + " run past the last face (" + std::to_string(faceCount - 1) + ")");
    covered += patch.faceCount;
    patches.push_back(std::move(patch));
  }
  s.expect(')', Where{"patch", -1, "list end"});
  expectEnd(s);
  if (covered != faceCount - firstBoundaryFace)
    s.fail("the patches hold " + std::to_string(covered) + " faces, the mesh has " +
           std::to_string(faceCount - firstBoundaryFace) + " boundary faces (faces without a neighbour)");
  return patches;
}

namespace detail {

void checkBinaryFoamPoints(const FoamPointsFile& original, const Eigen::MatrixX3d& points) {
  const FoamFileLayout& layout = original.layout;
  const std::int64_t n =
      std::int64_t(original.listEnd - original.listBegin + original.omittedBytes) / (3 * layout.scalarBytes);
  if (n != points.rows())
    throw MeshIoError(original.fileName + ": " + std::to_string(points.rows()) + " points given for a file of " +
                      std::to_string(n));
  if (layout.scalarBytes == 4) requireFloat32Points(points, "a binary OpenFOAM points file of scalar=32");
}

char* storeFoamPoints(const FoamFileLayout& layout, const Eigen::MatrixX3d& points, Eigen::Index first, Eigen::Index last,
                      char* out) {
  for (Eigen::Index i = first; i < last; ++i)
    for (int c = 0; c < 3; ++c)
      out = layout.scalarBytes == 8 ? storeBinary(out, points(i, c), layout.bigEndian)
                                    : storeBinary(out, float(points(i, c)), layout.bigEndian);
  return out;
}

}  // namespace detail

std::string foamPointsBytes(const FoamPointsFile& original, const Eigen::MatrixX3d& points) {
  const std::string_view bytes = original.bytes;
  const FoamFileLayout& layout = original.layout;
  const std::string source = original.fileName;
  std::string out;
  if (layout.binary) {
    detail::checkBinaryFoamPoints(original, points);
    out.reserve(bytes.size() + original.omittedBytes);
    out.append(bytes.substr(0, original.listBegin));
    const std::size_t at = out.size();
    out.resize(at + std::size_t(points.rows()) * 3 * std::size_t(layout.scalarBytes));
    detail::storeFoamPoints(layout, points, 0, points.rows(), out.data() + at);
    out.append(bytes.substr(original.listEnd));
    return out;
  }
  // ASCII: walk the list's tokens as the reader did; everything between the numbers is copied.
  out.reserve(bytes.size() + bytes.size() / 2);
  out.append(bytes.substr(0, original.listBegin));
  FoamScanner s(bytes.substr(0, original.listEnd), source, original.listBegin, original.listLine);
  std::size_t copied = original.listBegin;
  char number[32];
  for (Eigen::Index i = 0;; ++i) {
    s.skipSpace();
    if (s.atEnd()) {
      if (i != points.rows())
        throw MeshIoError(source + ": " + std::to_string(points.rows()) + " points given for a file of " + std::to_string(i));
      break;
    }
    if (i >= points.rows())
      throw MeshIoError(source + ": " + std::to_string(points.rows()) + " points given for a file with more");
    s.expect('(', Where{"point", i});
    for (int c = 0; c < 3; ++c) {
      s.skipSpace();
      const std::size_t start = s.pos();
      const std::string_view token = s.numberToken();
      out.append(bytes.substr(copied, start - copied));
      double old = 0.0;
      const char* first = token.data() + (!token.empty() && token[0] == '+' ? 1 : 0);
      fast_float::from_chars(first, token.data() + token.size(), old);
      const double value = points(i, c);
      if (std::memcmp(&old, &value, sizeof value) == 0) {
        out.append(token);
      } else {
        if (!std::isfinite(value))
          throw MeshIoError(source + ": " + Where{"point", i}.text() + ": non-finite coordinate");
        out.append(number, std::size_t(detail::putNumber(number, value) - number));
      }
      copied = s.pos();
    }
    s.expect(')', Where{"point", i});
  }
  out.append(bytes.substr(copied));
  return out;
}

std::string gunzipBytes(std::string_view compressed, const std::string& source, ReadBudget& budget) {
  z_stream z{};
  if (inflateInit2(&z, 15 + 32) != Z_OK) throw MeshIoError(source + ": cannot start zlib");
  struct End {
    z_stream* z;
    ~End() { inflateEnd(z); }
  } end{&z};
  std::string out;
  std::uint64_t charged = 0;
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  std::size_t inLeft = compressed.size();
  std::size_t produced = 0;
  for (;;) {
    if (produced == out.size()) {
      // Grow by doubling, from a first guess of four times the compressed size; charged first.
      const std::size_t want = std::max<std::size_t>({std::size_t(1) << 16, 2 * out.size(), std::min<std::size_t>(4 * compressed.size(), std::size_t(1) << 30)});
      try {
        budget.chargeBytes(want - charged, 1, source + ": decompressed data");
      } catch (const ReadLimitError& e) {
        throw MeshIoError(source + ": the compressed file expands past " + std::to_string(produced) +
                          " bytes and is refused (" + e.what() + ")");
      }
      charged = want;
      out.resize(want);
    }
    const uInt chunkIn = uInt(std::min<std::size_t>(inLeft, UINT_MAX));
    const uInt chunkOut = uInt(std::min<std::size_t>(out.size() - produced, UINT_MAX));
    z.avail_in = chunkIn;
    z.next_out = reinterpret_cast<Bytef*>(out.data() + produced);
    z.avail_out = chunkOut;
    const int result = inflate(&z, Z_NO_FLUSH);
    inLeft -= chunkIn - z.avail_in;
    produced += chunkOut - z.avail_out;
    if (result == Z_STREAM_END) {
      if (inLeft == 0) break;
      inflateReset(&z);  // a further gzip member follows (as `cat a.gz b.gz`)
      continue;
    }
    if (result == Z_BUF_ERROR && inLeft == 0)
      throw MeshIoError(source + ": truncated: the compressed data end before the gzip stream does");
    if (result != Z_OK && result != Z_BUF_ERROR)
      throw MeshIoError(source + ": not valid gzip data (" + (z.msg != nullptr ? z.msg : "zlib error") + ")");
  }
  out.resize(produced);
  budget.releaseBytes(charged - produced);
  return out;
}

std::string gzipBytes(std::string_view bytes, const std::string& source) {
  z_stream z{};
  if (deflateInit2(&z, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw MeshIoError(source + ": cannot start zlib");
  struct End {
    z_stream* z;
    ~End() { deflateEnd(z); }
  } end{&z};
  std::string out;
  char buffer[1 << 16];
  std::size_t inLeft = bytes.size();
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  for (;;) {
    const uInt chunkIn = uInt(std::min<std::size_t>(inLeft, std::size_t(1) << 30));
    z.avail_in = chunkIn;
    z.next_out = reinterpret_cast<Bytef*>(buffer);
    z.avail_out = sizeof buffer;
    const int result = deflate(&z, chunkIn == inLeft ? Z_FINISH : Z_NO_FLUSH);
    inLeft -= chunkIn - z.avail_in;
    out.append(buffer, sizeof buffer - z.avail_out);
    if (result == Z_STREAM_END) break;
    if (result != Z_OK && result != Z_BUF_ERROR) throw MeshIoError(source + ": gzip compression failed");
  }
  return out;
}

}  // namespace ffdkit::meshio
