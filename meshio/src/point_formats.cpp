// Point files: .xyz text (one "x y z" per line, '#' comments) and numpy .npy arrays of shape
// (N, 3) (https://numpy.org/doc/stable/reference/generated/numpy.lib.format.html).
#include <algorithm>
#include <climits>

#include "formats.h"
#include "parse_support.h"

namespace ffdkit::meshio::detail {

Eigen::MatrixX3d readXyzPoints(std::string_view bytes, const std::string& source, int firstLine, long long firstPoint,
                               ReadBudget& budget) {
  TextCursor text(bytes, source, firstLine);
  // One point per line at most: the line count bounds the first allocation by the file's size
  // (and the budget bounds it too; the budget's refusal names the line).
  const auto lines = Eigen::Index(std::count(bytes.begin(), bytes.end(), '\n') + 1);
  PointSink points(lines, &budget, "xyz points");
  try {
    while (!text.atEnd()) {
      text.skipBlanks();
      if (text.atLineEnd(true)) {
        text.nextLine();
        continue;
      }
      const Where where{"point", firstPoint + points.rows()};
      const double x = text.number(where), y = text.number(where), z = text.number(where);
      text.skipBlanks();
      if (!text.atLineEnd(true)) text.fail(where.text() + ": expected three numbers \"x y z\", got more");
      points.add(x, y, z);
      text.nextLine();
    }
  } catch (const ReadLimitError& e) {
    text.fail(e.what());
  }
  return points.take();
}

XyzCounts countXyz(std::string_view bytes) {
  XyzCounts counts;
  for (std::size_t at = 0; at < bytes.size();) {
    std::size_t end = bytes.find('\n', at);
    if (end == std::string_view::npos) end = bytes.size();
    else ++counts.lines;
    // A point line, as readXyzPoints decides: something before the line's end or a '#'.
    std::size_t k = at;
    while (k < end && (bytes[k] == ' ' || bytes[k] == '\t' || bytes[k] == '\r')) ++k;
    if (k < end && bytes[k] != '\n' && bytes[k] != '#') ++counts.points;
    at = end + (end < bytes.size() ? 1 : 0);
  }
  return counts;
}

MeshData readXyz(std::string_view bytes, const std::string& source, ReadBudget& budget) {
  MeshData mesh;
  mesh.points = readXyzPoints(bytes, source, 1, 0, budget);
  if (mesh.points.rows() == 0) throw MeshIoError(source + ": the file has no points");
  if (mesh.points.rows() > INT_MAX) throw MeshIoError(source + ": more points than ffdkit indexes");
  return mesh;
}

void writeXyz(ByteSink& out, const MeshData& mesh) { writeXyzPoints(out, mesh.points); }

void writeXyzPoints(ByteSink& out, const Eigen::MatrixX3d& points) {
  writeRows(out, points.rows(), 3 * 25, [&](char* at, Eigen::Index i) {
    at = putNumber(at, points(i, 0));
    *at++ = ' ';
    at = putNumber(at, points(i, 1));
    *at++ = ' ';
    at = putNumber(at, points(i, 2));
    *at++ = '\n';
    return at;
  });
}

namespace {

// The header dictionary of an .npy file: {'descr': '<f8', 'fortran_order': False, 'shape': (N, 3), }
struct NpyHeader {
  std::string descr;
  bool fortranOrder = false;
  std::vector<long long> shape;
};

class DictParser {
 public:
  DictParser(std::string_view text, const ByteCursor& errors) : text_(text), errors_(errors) {}

  NpyHeader parse() {
    NpyHeader h;
    bool descr = false, order = false, shape = false;
    expect('{');
    for (;;) {
      skipSpaces();
      if (peek() == '}') break;
      const std::string key = quoted();
      expect(':');
      if ((key == "descr" && descr) || (key == "fortran_order" && order) || (key == "shape" && shape))
        fail("'" + key + "' is given twice");
      skipSpaces();
      if (key == "descr") {
        h.descr = quoted();
        descr = true;
      } else if (key == "fortran_order") {
        h.fortranOrder = word() == "True";
        order = true;
      } else if (key == "shape") {
        expect('(');
        for (;;) {
          skipSpaces();
          if (peek() == ')') break;
          long long value = 0;
          const auto r = std::from_chars(text_.data() + pos_, text_.data() + text_.size(), value);
          if (r.ec != std::errc() || value < 0) fail("a shape entry is not a size");
          pos_ = std::size_t(r.ptr - text_.data());
          h.shape.push_back(value);
          if (h.shape.size() > 8) fail("too many dimensions");
          skipSpaces();
          if (peek() == ',') ++pos_;
        }
        ++pos_;
        shape = true;
      } else {
        fail("unknown key '" + key + "'");
      }
      skipSpaces();
      if (peek() == ',') ++pos_;
    }
    if (!descr || !order || !shape) fail("the header needs 'descr', 'fortran_order' and 'shape'");
    return h;
  }

 private:
  char peek() const { return pos_ < text_.size() ? text_[pos_] : '\0'; }
  void skipSpaces() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\n')) ++pos_;
  }
  void expect(char c) {
    skipSpaces();
    if (peek() != c) fail(std::string("expected '") + c + "'");
    ++pos_;
  }
  std::string quoted() {
    skipSpaces();
    const char quote = peek();
    if (quote != '\'' && quote != '"') fail("expected a quoted string");
    const std::size_t end = text_.find(quote, pos_ + 1);
    if (end == std::string_view::npos) fail("unterminated string");
    std::string value(text_.substr(pos_ + 1, end - pos_ - 1));
    pos_ = end + 1;
    return value;
  }
  std::string word() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && std::isalpha(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    const std::string w(text_.substr(start, pos_ - start));
    if (w != "True" && w != "False") fail("expected True or False");
    return w;
  }
  [[noreturn]] void fail(const std::string& message) const { errors_.fail("header: " + message); }

  std::string_view text_;
  const ByteCursor& errors_;
  std::size_t pos_ = 0;
};

}  // namespace

NpyLayout readNpyHeader(std::string_view prefix, std::uint64_t fileBytes, const std::string& source) {
  ByteCursor data(prefix, source);
  data.need(10, {"header"});
  if (prefix.substr(0, 6) != "\x93NUMPY") data.fail("not a numpy .npy file");
  data.skip(6);
  const int major = data.take<std::uint8_t>(false);
  data.skip(1);
  if (major < 1 || major > 3) data.fail("npy format version " + std::to_string(major) + " is not known (1..3)");
  std::size_t headerLength = 0;
  if (major == 1) {
    headerLength = data.take<std::uint16_t>(false);
  } else {
    data.need(4, {"header"});
    headerLength = data.take<std::uint32_t>(false);
  }
  data.need(headerLength, {"header"});
  const NpyHeader header = DictParser(prefix.substr(data.offset(), headerLength), data).parse();
  data.skip(headerLength);

  if (header.descr.size() != 3 || (header.descr[0] != '<' && header.descr[0] != '>' && header.descr[0] != '=') ||
      header.descr[1] != 'f' || (header.descr[2] != '4' && header.descr[2] != '8'))
    data.fail("dtype '" + header.descr + "' is not a float array (expected <f4, <f8, >f4 or >f8)");
  if (header.shape.size() != 2 || header.shape[1] != 3)
    data.fail("expected an array of shape (N, 3)");
  NpyLayout layout;
  layout.bigEndian = header.descr[0] == '>';
  layout.itemSize = header.descr[2] == '4' ? 4 : 8;
  layout.fortranOrder = header.fortranOrder;
  layout.dataOffset = data.offset();
  const long long n = header.shape[0];
  const std::size_t left = std::size_t(fileBytes) - data.offset();
  if (n == 0) data.fail("the file has no points");
  if (std::size_t(n) > left / (3 * layout.itemSize) || std::size_t(n) * 3 * layout.itemSize != left)
    data.fail("shape (" + std::to_string(n) + ", 3) needs " + (std::size_t(n) > SIZE_MAX / 24 ? std::string("more") : std::to_string(std::size_t(n) * 3 * layout.itemSize)) +
              " bytes of data, the file has " + std::to_string(left));
  if (n > INT_MAX) data.fail("more points than ffdkit indexes");
  layout.rows = n;
  return layout;
}

void decodeNpyRows(const NpyLayout& layout, std::string_view bytes, long long first, Eigen::MatrixX3d& points,
                   const std::string& source) {
  ByteCursor data(bytes, source, 0, layout.dataOffset + std::size_t(first) * 3 * layout.itemSize);
  data.need(std::size_t(points.rows()) * 3 * layout.itemSize, {"point", first + points.rows() - 1});
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double value = layout.itemSize == 4 ? double(data.take<float>(layout.bigEndian)) : data.take<double>(layout.bigEndian);
      if (!std::isfinite(value)) data.fail(Where{"point", first + i}.text() + ": non-finite coordinate");
      points(i, c) = value;
    }
}

MeshData readNpy(std::string_view bytes, const std::string& source, ReadBudget& budget) {
  const NpyLayout layout = readNpyHeader(bytes, bytes.size(), source);
  const long long n = layout.rows;
  budget.chargePoints(std::uint64_t(n), "shape (" + std::to_string(n) + ", 3)");
  MeshData mesh;
  mesh.points.resize(Eigen::Index(n), 3);
  if (!layout.fortranOrder) {
    decodeNpyRows(layout, bytes.substr(layout.dataOffset), 0, mesh.points, source);
    return mesh;
  }
  ByteCursor data(bytes, source, layout.dataOffset);
  for (long long k = 0; k < 3 * n; ++k) {
    // Fortran order: column by column.
    const long long row = k % n;
    const int column = int(k / n);
    const double value = layout.itemSize == 4 ? double(data.take<float>(layout.bigEndian)) : data.take<double>(layout.bigEndian);
    if (!std::isfinite(value)) data.fail(Where{"point", row}.text() + ": non-finite coordinate");
    mesh.points(row, column) = value;
  }
  return mesh;
}

std::string npyHeader(Eigen::Index rows) {
  std::string dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + std::to_string(rows) + ", 3), }";
  // Magic, version 1.0, a 2-byte length, then the dictionary padded with spaces and a newline
  // so that the data start on a multiple of 64 bytes.
  const std::size_t total = (10 + dict.size() + 1 + 63) / 64 * 64;
  dict.append(total - 10 - dict.size() - 1, ' ').append("\n");
  std::string out("\x93NUMPY\x01\x00", 8);
  appendBinary(out, std::uint16_t(dict.size()), false);
  out += dict;
  return out;
}

void writeNpy(ByteSink& sink, const MeshData& mesh) {
  BinaryChunks chunks(sink);
  chunks.bytes(npyHeader(mesh.points.rows()));
  writeNpyRecords(chunks, mesh.points);
  chunks.flush();
}

void writeNpyRecords(BinaryChunks& chunks, const Eigen::MatrixX3d& points) {
  chunks.records(points.rows(), kNpyRecordBytes, [&](char* at, Eigen::Index i) {
    for (int c = 0; c < 3; ++c) at = storeBinary(at, points(i, c), false);
  });
}

}  // namespace ffdkit::meshio::detail
