// ffdkit-cli on rational lattices (control-point weights, Lamousin & Waggenspack 1994): info
// names them with the range of their weights; a deformation with them matches the library.
#include <gtest/gtest.h>

#include <filesystem>

#include <unistd.h>

#include "cli_runner.h"
#include "ffdkit/scenes/widget_file.h"

namespace ffdkit::cli::test {
namespace {

namespace fs = std::filesystem;

TEST(CliWeights, InfoNamesARationalLatticeAndTheRangeOfItsWeights) {
  const fs::path dir = fs::temp_directory_path() / ("ffdkit-cli-weights-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  widgets::WidgetModel model;
  const widgets::WidgetId plain = model.addLattice("plain", Eigen::Vector3i(2, 2, 2));
  const widgets::WidgetId weighted = model.addLattice("weighted", Eigen::Vector3i(3, 3, 3));
  (void)plain;
  model.setWeight(weighted, 4, 0.5);
  model.setWeight(weighted, 13, 3.0);
  scenes::writeWidgetFile(dir / "tool.json", model);
  const CliResult r = runCli({"info", (dir / "tool.json").string()});
  EXPECT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_NE(r.out.find("lattice weighted: 3x3x3 control points, root, 0 cells, rational (weights 0.5 to 3)"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("lattice plain: 2x2x2 control points, root, 0 cells\n"), std::string::npos) << r.out;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ffdkit::cli::test
