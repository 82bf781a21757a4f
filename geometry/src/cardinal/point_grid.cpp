#include "ffdkit/geometry/cardinal/point_grid.h"

#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>

#include "ffdkit/geometry/cardinal/cardinal_error.h"

namespace ffdkit::geometry::cardinal {

Eigen::MatrixX3d PointGrid::row(int i) const {
  Eigen::MatrixX3d out(cols, 3);
  for (int j = 0; j < cols; ++j) out.row(j) = (*this)(i, j).transpose();
  return out;
}

Eigen::MatrixX3d PointGrid::col(int j) const {
  Eigen::MatrixX3d out(rows, 3);
  for (int i = 0; i < rows; ++i) out.row(i) = (*this)(i, j).transpose();
  return out;
}

double PointGrid::boundingBoxDiagonal() const {
  if (data.empty()) return 0.0;
  Eigen::Vector3d lo = data.front(), hi = data.front();
  for (const auto& p : data) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

namespace {

// Next non-blank, non-comment line; false at end of input.
bool nextDataLine(std::istream& in, std::string& line, int& lineNo) {
  while (std::getline(in, line)) {
    ++lineNo;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    return true;
  }
  return false;
}

}  // namespace

PointGrid readPointGrid(std::istream& in, const std::string& sourceName) {
  std::string line;
  int lineNo = 0;
  if (!nextDataLine(in, line, lineNo)) {
    throw CardinalSplineError(sourceName + ": expected a header 'rows cols', got end of input");
  }
  int rows = 0, cols = 0;
  {
    std::istringstream header(line);
    if (!(header >> rows >> cols) || rows < 1 || cols < 1) {
      throw CardinalSplineError(sourceName + ":" + std::to_string(lineNo) +
                                ": expected 'rows cols' with two positive integers, got '" +
                                line + "'");
    }
  }
  PointGrid grid(rows, cols);
  for (int k = 0; k < rows * cols; ++k) {
    if (!nextDataLine(in, line, lineNo)) {
      throw CardinalSplineError(sourceName + ": expected " + std::to_string(rows * cols) +
                                " points (" + std::to_string(rows) + " x " +
                                std::to_string(cols) + "), got " + std::to_string(k));
    }
    std::istringstream pt(line);
    Eigen::Vector3d p;
    if (!(pt >> p.x() >> p.y() >> p.z())) {
      throw CardinalSplineError(sourceName + ":" + std::to_string(lineNo) +
                                ": expected three numbers 'x y z', got '" + line + "'");
    }
    grid.data[static_cast<std::size_t>(k)] = p;
  }
  return grid;
}

PointGrid readPointGrid(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw CardinalSplineError(path.string() + ": cannot open point grid file");
  return readPointGrid(in, path.string());
}

void writePointGrid(std::ostream& out, const PointGrid& grid) {
  out << grid.rows << ' ' << grid.cols << '\n' << std::setprecision(17);
  for (const auto& p : grid.data) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
}

void writePointGrid(const std::filesystem::path& path, const PointGrid& grid) {
  std::ofstream out(path);
  if (!out) throw CardinalSplineError(path.string() + ": cannot open for writing");
  writePointGrid(out, grid);
}

}  // namespace ffdkit::geometry::cardinal
