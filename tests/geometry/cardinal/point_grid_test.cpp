#include "ffdkit/geometry/cardinal/point_grid.h"

#include <sstream>

#include <gtest/gtest.h>

#include "ffdkit/geometry/cardinal/cardinal_error.h"

namespace ffdkit::geometry::cardinal {
namespace {

TEST(PointGrid, RoundTripsThroughTheTextFormat) {
  PointGrid g(3, 2);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 2; ++j) g(i, j) = Eigen::Vector3d(i + 0.1, j / 3.0, -i * j * 1e-7);
  std::stringstream s;
  writePointGrid(s, g);
  const PointGrid r = readPointGrid(s);
  ASSERT_EQ(r.rows, 3);
  ASSERT_EQ(r.cols, 2);
  for (std::size_t k = 0; k < g.data.size(); ++k) EXPECT_EQ(r.data[k], g.data[k]);
}

TEST(PointGrid, ReadsCommentsAndReportsBadLines) {
  std::istringstream ok("# grid\n2 1\n\n0 0 0\n1 2 3\n");
  EXPECT_EQ(readPointGrid(ok)(1, 0), Eigen::Vector3d(1, 2, 3));
  std::istringstream bad("2 1\n0 0 0\n1 2\n");
  try {
    readPointGrid(bad, "grid.txt");
    FAIL();
  } catch (const CardinalSplineError& e) {
    EXPECT_NE(std::string(e.what()).find("grid.txt:3"), std::string::npos) << e.what();
  }
  std::istringstream shortInput("2 2\n0 0 0\n");
  EXPECT_THROW(readPointGrid(shortInput), CardinalSplineError);
  EXPECT_THROW(readPointGrid(std::filesystem::path("/nonexistent/grid.txt")), CardinalSplineError);
}

TEST(PointGrid, RowsColumnsAndBoundingBox) {
  PointGrid g(2, 3);
  g(1, 2) = Eigen::Vector3d(3, 4, 0);
  EXPECT_EQ(g.row(1).row(2), Eigen::RowVector3d(3, 4, 0));
  EXPECT_EQ(g.col(2).row(1), Eigen::RowVector3d(3, 4, 0));
  EXPECT_DOUBLE_EQ(g.boundingBoxDiagonal(), 5.0);
}

}  // namespace
}  // namespace ffdkit::geometry::cardinal
