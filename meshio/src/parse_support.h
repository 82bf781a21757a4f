#pragma once
// Cursors over a file's bytes that check before they read, and growing sinks for points and
// cells. Private to meshio: every reader parses from memory through these, so every bound is
// checked in one place.

#include <algorithm>
#include <atomic>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>
#include <thread>
#include <type_traits>
#include <vector>

#include <fast_float/fast_float.h>


#include "ffdkit/ffd/huge_pages.h"

#include "ffdkit/meshio/atomic_write.h"
#include "ffdkit/meshio/mesh_data.h"
#include "ffdkit/meshio/read_limits.h"

namespace ffdkit::meshio::detail {

using ffd::adviseHugePages;

/// Names an element in a message: "face 12", "vertex 7 (x)". Built into text only on failure,
/// so that a reader's hot loop allocates nothing.
struct Where {
  const char* kind;
  long long index = -1;          ///< -1: no index ("header")
  std::string_view detail = {};  ///< a property name, or empty
  std::string text() const {
    std::string t = kind;
    if (index >= 0) t.append(" ").append(std::to_string(index));
    if (!detail.empty()) t.append(" (").append(detail).append(")");
    return t;
  }
};

/// Text read token by token with the line number kept for messages (`file:12: ...`).
class TextCursor {
 public:
  /// `firstLine`: the line number of `text`'s first line in the file.
  TextCursor(std::string_view text, const std::string& source, int firstLine = 1)
      : text_(text), source_(source), line_(firstLine) {}

  bool atEnd() const { return pos_ >= text_.size(); }
  int line() const { return line_; }
  std::size_t bytesLeft() const { return text_.size() - pos_; }

  /// Skips spaces, tabs and carriage returns (not newlines).
  void skipBlanks() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\r')) ++pos_;
  }
  /// After skipBlanks: at a newline, a '#' comment (when `hashComments`), or the end.
  bool atLineEnd(bool hashComments = false) const {
    return pos_ >= text_.size() || text_[pos_] == '\n' || (hashComments && text_[pos_] == '#');
  }
  /// Moves past the next newline (or to the end).
  void nextLine() {
    const std::size_t newline = text_.find('\n', pos_);
    pos_ = newline == std::string_view::npos ? text_.size() : newline + 1;
    ++line_;
  }
  /// Fails unless only blanks (and a '#' comment when `hashComments`) are left on the line;
  /// then moves to the next line.
  void endLine(const Where& where, bool hashComments = false) {
    skipBlanks();
    if (!atLineEnd(hashComments)) fail(where.text() + ": unexpected '" + std::string(peekWord()) + "' at the end of the line");
    nextLine();
  }
  /// The next run of non-blank characters on this line (empty at the line's end).
  std::string_view word() {
    skipBlanks();
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !isBlankOrNewline(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }
  std::string_view peekWord() const {
    std::size_t end = pos_;
    while (end < text_.size() && !isBlankOrNewline(text_[end]) && end - pos_ < 40) ++end;
    return text_.substr(pos_, end - pos_);
  }
  /// The rest of the line (without the newline); the cursor stays.
  std::string_view restOfLine() const {
    const std::size_t newline = text_.find('\n', pos_);
    return text_.substr(pos_, (newline == std::string_view::npos ? text_.size() : newline) - pos_);
  }

  /// A finite number of type T (double or float; fast_float rounds the decimal text once,
  /// so the shortest text of a value reads back as exactly that value).
  template <class T = double>
  T number(const Where& where) {
    skipBlanks();
    const char* first = text_.data() + pos_;
    const char* last = text_.data() + text_.size();
    if (first < last && *first == '+') ++first;  // from_chars follows strtod except for '+'
    T value = 0;
    const auto result = fast_float::from_chars(first, last, value);
    if (result.ec != std::errc() || (result.ptr < last && !isBlankOrNewline(*result.ptr)))
      fail(where.text() + ": expected a number, got '" + std::string(peekWord()) + "'");
    if (!std::isfinite(value)) fail(where.text() + ": non-finite number '" + std::string(peekWord()) + "'");
    pos_ = std::size_t(result.ptr - text_.data());
    return value;
  }
  /// An integer in [lo, hi].
  long long integer(const Where& where, long long lo, long long hi) {
    skipBlanks();
    const char* first = text_.data() + pos_;
    const char* last = text_.data() + text_.size();
    if (first < last && *first == '+') ++first;
    long long value = 0;
    const auto result = std::from_chars(first, last, value);
    if (result.ec == std::errc::result_out_of_range)
      fail(where.text() + ": '" + std::string(peekWord()) + "' is out of range");
    if (result.ec != std::errc() || (result.ptr < last && !isBlankOrNewline(*result.ptr)))
      fail(where.text() + ": expected an integer, got '" + std::string(peekWord()) + "'");
    if (value < lo || value > hi)
      fail(where.text() + ": " + std::to_string(value) + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
    pos_ = std::size_t(result.ptr - text_.data());
    return value;
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw MeshIoError(source_ + ":" + std::to_string(line_) + ": " + message);
  }
  const std::string& source() const { return source_; }

  static bool isBlankOrNewline(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

 private:
  std::string_view text_;
  const std::string& source_;
  std::size_t pos_ = 0;
  int line_;
};

/// Binary data read value by value; every read is checked against the bytes left.
class ByteCursor {
 public:
  /// `base`: where `bytes` start in the file (a slice of it), for the offsets in messages.
  ByteCursor(std::string_view bytes, const std::string& source, std::size_t offset = 0, std::size_t base = 0)
      : bytes_(bytes), source_(source), pos_(offset), base_(base) {}

  std::size_t offset() const { return pos_; }
  std::size_t bytesLeft() const { return bytes_.size() - pos_; }
  const char* here() const { return bytes_.data() + pos_; }

  /// Fails unless `n` more bytes are there; `where` names what needs them.
  void need(std::size_t n, const Where& where) const {
    if (n > bytesLeft())
      fail("truncated: " + where.text() + " needs " + std::to_string(n) + " bytes at offset " + std::to_string(base_ + pos_) +
           ", the file has " + std::to_string(bytesLeft()) + " left");
  }
  void skip(std::size_t n) { pos_ += n; }  // after need()

  /// A value of type T, byte-swapped when `bigEndian`; call need() first.
  template <class T>
  T take(bool bigEndian) {
    T value;
    char raw[sizeof(T)];
    std::memcpy(raw, bytes_.data() + pos_, sizeof(T));
    if (bigEndian != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
    std::memcpy(&value, raw, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }

  [[noreturn]] void fail(const std::string& message) const { throw MeshIoError(source_ + ": " + message); }

 private:
  std::string_view bytes_;
  const std::string& source_;
  std::size_t pos_;
  std::size_t base_;
};

/// Rows appended to an Eigen matrix whose capacity doubles; shrink() trims it to the rows added.
/// With a budget, every row of capacity is charged to it before it is allocated (as a point,
/// when the sink holds points, and `extraBytesPerRow` more for what the reader keeps beside each
/// row), and the capacity never grows past what the budget has left: a read over its limit
/// fails at the first row too many, whatever the first capacity guessed. take() gives back the
/// charge of the capacity it trims.
template <class Matrix>
class RowSink {
 public:
  static constexpr std::uint64_t kRowBytes = sizeof(typename Matrix::Scalar) * std::uint64_t(Matrix::ColsAtCompileTime);

  /// `capacity`: a first guess (clamped to the budget). `what` names the rows in the budget's
  /// message ("OBJ vertices") and must outlive the sink.
  explicit RowSink(Eigen::Index capacity = 0, ReadBudget* budget = nullptr, std::string_view what = {},
                   std::uint64_t extraBytesPerRow = 0)
      : budget_(budget), what_(what), extraBytes_(extraBytesPerRow) {
    reserveTo(budget_ == nullptr ? capacity : std::min(capacity, affordableRows()));
    adviseHugePages(matrix_);
  }
  template <class... Values>
  void add(Values... values) {
    if (rows_ == matrix_.rows()) grow();
    // Column-major: coefficient (r, c) at data()[c * rows + r]. Plain stores: clang under UBSan
    // leaves Eigen's element access as a call per value, and a file has millions.
    static_assert(!Matrix::IsRowMajor);
    typename Matrix::Scalar* const row = matrix_.data() + rows_;
    const Eigen::Index stride = matrix_.rows();
    Eigen::Index c = 0;
    ((row[stride * c++] = values), ...);
    ++rows_;
  }
  Eigen::Index rows() const { return rows_; }
  Matrix take() {
    if (rows_ != matrix_.rows()) {
      const std::uint64_t trimmed = std::uint64_t(matrix_.rows() - rows_);
      matrix_.conservativeResize(rows_, Eigen::NoChange);
      if (budget_ != nullptr) release(trimmed);
    }
    return std::move(matrix_);
  }

 private:
  static constexpr bool kPoints = std::is_same_v<Matrix, Eigen::MatrixX3d>;

  // The rows the budget can still pay for.
  Eigen::Index affordableRows() const {
    const ReadLimits& limits = budget_->limits();
    const std::uint64_t each = kRowBytes + extraBytes_;
    const std::uint64_t bytesLeft = limits.maxMemoryBytes - std::min(limits.maxMemoryBytes, budget_->bytesCharged());
    std::uint64_t rows = bytesLeft / each;
    if constexpr (kPoints) rows = std::min(rows, limits.maxPoints - std::min(limits.maxPoints, budget_->pointsCharged()));
    return Eigen::Index(std::min<std::uint64_t>(rows, std::uint64_t(1) << 40));
  }
  void grow() {
    Eigen::Index capacity = std::max<Eigen::Index>(16, 2 * rows_);
    // One row past what is left, when nothing is: its charge throws the budget's error.
    if (budget_ != nullptr) capacity = rows_ + std::min(capacity - rows_, std::max<Eigen::Index>(1, affordableRows()));
    reserveTo(capacity);
  }
  void reserveTo(Eigen::Index capacity) {
    if (capacity <= matrix_.rows()) return;
    const std::uint64_t added = std::uint64_t(capacity - matrix_.rows());
    if (budget_ != nullptr) {
      if constexpr (kPoints) budget_->chargePoints(added, what_);
      else budget_->chargeBytes(added, kRowBytes, what_);
      if (extraBytes_ > 0) budget_->chargeBytes(added, extraBytes_, what_);
    }
    matrix_.conservativeResize(capacity, Eigen::NoChange);
  }
  void release(std::uint64_t rows) {
    if constexpr (kPoints) budget_->releasePoints(rows);
    else budget_->releaseBytes(rows * kRowBytes);
    budget_->releaseBytes(rows * extraBytes_);
  }

  Matrix matrix_ = Matrix(0, Matrix::ColsAtCompileTime);
  Eigen::Index rows_ = 0;
  ReadBudget* budget_ = nullptr;
  std::string_view what_;
  std::uint64_t extraBytes_ = 0;
};

using PointSink = RowSink<Eigen::MatrixX3d>;
using TriangleSink = RowSink<Eigen::MatrixX3i>;
using SegmentSink = RowSink<Eigen::MatrixX2i>;

/// Appends the shortest decimal text that reads back as exactly `value` (std::to_chars).
inline void appendNumber(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}
inline void appendNumber(std::string& out, float value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}
inline void appendNumber(std::string& out, long long value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

/// Writes the shortest decimal text of `value` (std::to_chars) at `at`; returns the end. `at` must
/// have room for 24 characters (the longest double, "-2.2250738585072014e-308").
inline char* putNumber(char* at, double value) { return std::to_chars(at, at + 24, value).ptr; }

/// Bytes collected in memory (meshFileBytes, the stream overload of writeMesh).
class StringSink final : public ByteSink {
 public:
  void write(std::string_view bytes) override { text.append(bytes); }
  std::string text;
};

/// Writes `rows` lines of text to `sink`, row i written by `formatRow(cursor, i) -> end` with at
/// most `maxRowBytes` bytes. Shortest-round-trip formatting costs ~50 ns a number, so large
/// blocks are cut into slices of 65,536 rows formatted side by side by one thread per core,
/// while this thread hands each finished slice to the sink in order (a file's disk write-back
/// then overlaps the formatting of later slices). The text is the same as a serial loop's.
template <class FormatRow>
void writeRows(ByteSink& sink, Eigen::Index rows, std::size_t maxRowBytes, FormatRow formatRow) {
  constexpr Eigen::Index kRowsPerSlice = 65536;
  const Eigen::Index slices = std::max<Eigen::Index>(1, (rows + kRowsPerSlice - 1) / kRowsPerSlice);
  struct Slice {
    std::unique_ptr<char[]> text;
    std::size_t size = 0;
    std::atomic<bool> ready{false};
  };
  std::vector<Slice> done(static_cast<std::size_t>(slices));
  std::atomic<Eigen::Index> next{0};
  auto format = [&] {
    for (Eigen::Index s; (s = next.fetch_add(1)) < slices;) {
      const Eigen::Index first = s * kRowsPerSlice, last = std::min(rows, first + kRowsPerSlice);
      Slice& slice = done[std::size_t(s)];
      slice.text = std::make_unique_for_overwrite<char[]>(std::size_t(last - first) * maxRowBytes);
      char* cursor = slice.text.get();
      for (Eigen::Index i = first; i < last; ++i) cursor = formatRow(cursor, i);
      slice.size = std::size_t(cursor - slice.text.get());
      slice.ready.store(true, std::memory_order_release);
      slice.ready.notify_one();
    }
  };
  if (slices == 1) {
    format();
    sink.write({done[0].text.get(), done[0].size});
    return;
  }
  const Eigen::Index hardware = std::max<Eigen::Index>(1, Eigen::Index(std::thread::hardware_concurrency()));
  std::vector<std::jthread> workers;
  for (Eigen::Index t = 0; t < std::min(hardware, slices); ++t) workers.emplace_back(format);
  try {
    for (Slice& slice : done) {
      slice.ready.wait(false, std::memory_order_acquire);
      sink.write({slice.text.get(), slice.size});
      slice.text.reset();
    }
  } catch (...) {
    next.store(slices);  // the workers stop after their current slice; their destructors join
    throw;
  }
}

/// Stores the raw bytes of `value` at `at` in the given byte order; returns the end.
template <class T>
char* storeBinary(char* at, T value, bool bigEndian) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if (bigEndian != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
  std::memcpy(at, raw, sizeof(T));
  return at + sizeof(T);
}

/// Appends the raw bytes of `value` in the given byte order.
template <class T>
void appendBinary(std::string& out, T value, bool bigEndian) {
  char raw[sizeof(T)];
  out.append(raw, storeBinary(raw, value, bigEndian));
}

/// A binary file streamed to its sink through one small buffer, handed on whenever it fills.
/// A writer that built the whole file first would fill as many bytes of fresh memory as the
/// file has (38 MB for a 1M-vertex PLY with its faces) and then copy them again into the page
/// cache; 1 MiB stays in cache. On this project's virtual machine, where fresh pages are the
/// expensive part, the 1M-vertex PLY (`BM_WriteMesh`) takes 28-33 ms streamed against 47 ms
/// built whole.
class BinaryChunks {
 public:
  static constexpr std::size_t kCapacity = std::size_t(1) << 20;

  explicit BinaryChunks(ByteSink& sink) : sink_(sink), buffer_(std::make_unique_for_overwrite<char[]>(kCapacity)) {}

  /// Bytes of any size (a header).
  void bytes(std::string_view data) {
    while (!data.empty()) {
      if (used_ == kCapacity) flush();
      const std::size_t n = std::min(data.size(), kCapacity - used_);
      std::memcpy(buffer_.get() + used_, data.data(), n);
      used_ += n;
      data.remove_prefix(n);
    }
  }

  /// `count` records of exactly `recordBytes` (<= kCapacity) bytes each: record i is stored by
  /// `store(at, i)`, which writes its bytes at `at`.
  template <class Store>
  void records(Eigen::Index count, std::size_t recordBytes, Store store) {
    for (Eigen::Index i = 0; i < count;) {
      if (kCapacity - used_ < recordBytes) flush();
      const Eigen::Index room = Eigen::Index((kCapacity - used_) / recordBytes);
      const Eigen::Index last = std::min(count, i + room);
      char* at = buffer_.get() + used_;
      for (; i < last; ++i, at += recordBytes) store(at, i);
      used_ = std::size_t(at - buffer_.get());
    }
  }

  /// Hands what is gathered to the sink; call once after the last record.
  void flush() {
    if (used_ > 0) sink_.write({buffer_.get(), used_});
    used_ = 0;
  }

 private:
  ByteSink& sink_;
  std::unique_ptr<char[]> buffer_;
  std::size_t used_ = 0;
};

}  // namespace ffdkit::meshio::detail
