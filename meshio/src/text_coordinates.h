#pragma once
// Reading and rewriting the coordinates of a text mesh format in place. Private to meshio: the
// Gmsh (ASCII), SU2, UNV, Elmer, LS-DYNA and Kratos readers scan their files with LineScanner
// and note where each coordinate's text is (CoordinateSpans); the pass-through writers give back
// the file's bytes with only those spans replaced, so comments, tags, markers, element blocks
// and layout come back byte for byte.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/meshio/mesh_data.h"

namespace ffdkit::meshio::detail {

/// A text file read token by token with its line number kept for messages ("file:12: ...").
class LineScanner {
 public:
  LineScanner(std::string_view text, const std::string& source) : text_(text), source_(source) {}

  std::size_t pos() const { return pos_; }
  int line() const { return line_; }
  bool atEnd() const { return pos_ >= text_.size(); }
  std::size_t bytesLeft() const { return text_.size() - pos_; }
  std::string_view text() const { return text_; }

  /// Skips blanks (spaces, tabs, carriage returns); newlines too when `newlines`.
  void skipBlanks(bool newlines = true);
  /// At a newline or the end, after blanks.
  bool atLineEnd();
  /// The rest of the current line (without '\r\n'), and moves past its newline.
  std::string_view takeLine();
  /// The next token: a run of characters that are not blanks, newlines or `extraSeparator`
  /// ('\0': none). Empty at the end of the text (or of the line, when !newlines).
  std::string_view token(bool newlines = true, char extraSeparator = '\0');
  /// An integer in [lo, hi]; `what` names it for the message ("node 12 tag").
  long long integer(std::string_view what, long long lo, long long hi, bool newlines = true);
  /// A finite number; Fortran's 'D' exponent is read as 'E' when `fortran`. Returns its span
  /// through `start` and `length` when they are not null.
  double number(std::string_view what, bool newlines = true, std::size_t* start = nullptr, std::size_t* length = nullptr,
                bool fortran = false, char extraSeparator = '\0');
  /// Moves to `pos` (a position in the text), counting the newlines passed (unless messages
  /// name byte offsets).
  void moveTo(std::size_t pos);
  /// From now on messages name the byte offset instead of the line ("file: byte offset 1234:
  /// ..."): for a file whose binary data make line numbers meaningless.
  void useByteOffsets() { byteOffsets_ = true; }

  [[noreturn]] void fail(const std::string& message) const;
  [[noreturn]] void failAt(int line, const std::string& message) const;
  const std::string& source() const { return source_; }

 private:
  std::string_view text_;
  const std::string& source_;
  std::size_t pos_ = 0;
  int line_ = 1;
  bool byteOffsets_ = false;
};

/// Parses a number token as the readers do (a leading '+' allowed; with `fortran`, 'D' or 'd'
/// as the exponent letter). Returns false when `token` is not a whole finite number.
bool parseNumberToken(std::string_view token, double& value, bool fortran = false);

/// How a format writes a coordinate that changed.
struct NumberStyle {
  /// Digits after the point in exponent notation ("%.{precision}E"); -1: the shortest text that
  /// reads back as the value (std::to_chars).
  int precision = -1;
  /// The exponent letter for `precision` >= 0 ('E', or Fortran's 'D').
  char exponent = 'E';
  /// Each coordinate is a fixed-width field (the span is the whole field): the new text is
  /// right-aligned in it and its precision lowered until it fits.
  bool fixedWidth = false;
  /// Fortran 'D' exponents in the old text (to compare the old value).
  bool fortran = false;
  /// A fixed-width field that follows another value directly keeps one blank before its text
  /// (the format is read by splitting at blanks, as UNV's readers do).
  bool separated = false;
};

/// Where the coordinates of each point are in a text file: point i's coordinate c (c < perPoint)
/// is the span starts[perPoint i + c] of lengths[perPoint i + c] bytes.
struct CoordinateSpans {
  int perPoint = 3;
  std::vector<std::uint64_t> starts;
  std::vector<std::uint32_t> lengths;
  NumberStyle style;

  void add(std::size_t start, std::size_t length) {
    starts.push_back(start);
    lengths.push_back(std::uint32_t(length));
  }
  std::int64_t pointCount() const { return perPoint == 0 ? 0 : std::int64_t(starts.size()) / perPoint; }
};

/// `original` with each coordinate span replaced by the text of `points` (#P x 3; the first
/// spans.perPoint columns are used): a value whose bits did not change keeps its text.
/// @throws MeshIoError naming `source` for a point count that differs, a non-finite value, or a
///   value that does not fit a fixed-width field.
std::string replaceCoordinates(std::string_view original, const CoordinateSpans& spans, const Eigen::MatrixX3d& points,
                               const std::string& source);

}  // namespace ffdkit::meshio::detail
