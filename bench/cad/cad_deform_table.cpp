// The table of docs/cad.md: for each sample part (cad/sample_parts.h), the exact composition and the
// pole-moving method with the same lattice, then a quadratic B-spline and a cylindrical lattice: degrees, deviation from the FFD of the original surface,
// edge-face gaps, validity, time (median of --repetitions runs) and STEP file sizes.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "cad_test_support.h"
#include "ffdkit/cad/cad_check.h"
#include "ffdkit/cad/cad_deform.h"
#include "ffdkit/cad/cad_error.h"
#include "ffdkit/cad/cad_io.h"
#include "ffdkit/cad/sample_parts.h"

namespace {

using namespace ffdkit;
using namespace ffdkit::cad;

Eigen::Vector3i countsFor(SamplePart sample) {
  switch (sample) {
    case SamplePart::Blade: return {2, 2, 3};
    case SamplePart::BentPipe: return {2, 3, 2};
    default: return {3, 3, 2};
  }
}

struct Row {
  CadDeformReport report;
  CadCheck check;
  double medianSeconds = 0.0;
  std::uintmax_t stepBytes = 0;
};

Row run(const CadModel& model, const ffd::Lattice& lattice, CadMethod method, int repetitions, const std::filesystem::path& file) {
  CadDeformOptions options;
  options.method = method;
  std::vector<double> seconds;
  CadDeformResult result;
  for (int r = 0; r < repetitions; ++r) {
    result = deformCad(model, lattice, options);
    seconds.push_back(result.report.seconds);
  }
  std::sort(seconds.begin(), seconds.end());
  options.samples = 9;
  Row row;
  row.report = deformCad(model, lattice, options).report;
  row.check = checkModel(result.model);
  row.medianSeconds = seconds[seconds.size() / 2];
  writeStep(result.model, file);
  row.stepBytes = std::filesystem::file_size(file);
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  int repetitions = 5;
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "--repetitions") == 0) repetitions = std::max(1, std::atoi(argv[i + 1]));
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / ("ffdkit-cad-table-" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  std::printf("| part | faces | lattice | method | degree | approximated faces | max deviation / size | max gap | valid | time (ms) | STEP in -> out (kB) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (SamplePart sample : allSampleParts()) {
    const CadModel model = makeSamplePart(sample);
    const std::string name = samplePartName(sample);
    const double size = model.bounds().diagonal().norm();
    const Eigen::Vector3i counts = countsFor(sample);
    const ffd::Lattice lattice = test::deformedLatticeAround(model.bounds(), counts, 0.08);
    const auto in = folder / (name + ".step");
    writeStep(model, in);
    const auto inBytes = std::filesystem::file_size(in);
    for (CadMethod method : {CadMethod::Exact, CadMethod::Poles}) {
      const bool exact = method == CadMethod::Exact;
      const Row row = run(model, lattice, method, repetitions, folder / (name + (exact ? "-exact" : "-poles") + ".step"));
      std::printf("| %s | %d | %dx%dx%d | %s | %d | %d | %.1e | %.1e | %s | %.1f | %.0f -> %.0f |\n", name.c_str(),
                  row.report.faces, counts[0], counts[1], counts[2], exact ? "exact" : "poles", row.report.maxDegree,
                  row.report.approximatedFaces, row.report.maxDeviation / size, row.report.maxGap,
                  row.check.valid ? "yes" : "no", 1e3 * row.medianSeconds, inBytes / 1024.0, row.stepBytes / 1024.0);
      std::fflush(stdout);
    }
    // A quadratic B-spline lattice of 4 x 4 x 4 points: exact cell by cell where the knot planes
    // cross a face along its parameter lines, approximated within 1e-6 x size elsewhere.
    const ffd::Lattice bspline = test::deformedLatticeAround(model.bounds(), {4, 4, 4}, 0.08, ffd::AxisBasis::bspline(2));
    try {
      const Row row = run(model, bspline, CadMethod::Exact, repetitions, folder / (name + "-bspline.step"));
      std::printf("| %s | %d | 4x4x4 quadratic B-spline | exact + approximated | %d | %d | %.1e | %.1e | %s | %.1f | %.0f -> %.0f |\n",
                  name.c_str(), row.report.faces, row.report.maxDegree, row.report.approximatedFaces,
                  row.report.maxDeviation / size, row.report.maxGap, row.check.valid ? "yes" : "no",
                  1e3 * row.medianSeconds, inBytes / 1024.0, row.stepBytes / 1024.0);
    } catch (const CadError& error) {
      std::printf("| %s | | 4x4x4 quadratic B-spline | failed: %s |\n", name.c_str(), error.what());
    }
    std::fflush(stdout);
    // A quadratic cylindrical lattice (3 x 8 x 3, axis along z): no polynomial of world
    // coordinates, so every face and edge is approximated within 1e-6 x size.
    try {
      const Row row = run(model, test::cylinderAround(model), CadMethod::Exact, repetitions, folder / (name + "-cylinder.step"));
      std::printf("| %s | %d | 3x8x3 quadratic cylindrical | approximated | %d | %d | %.1e | %.1e | %s | %.1f | %.0f -> %.0f |\n",
                  name.c_str(), row.report.faces, row.report.maxDegree, row.report.approximatedFaces,
                  row.report.maxDeviation / size, row.report.maxGap, row.check.valid ? "yes" : "no",
                  1e3 * row.medianSeconds, inBytes / 1024.0, row.stepBytes / 1024.0);
    } catch (const CadError& error) {
      std::printf("| %s | | 3x8x3 quadratic cylindrical | failed: %s |\n", name.c_str(), error.what());
    }
    std::fflush(stdout);
  }
  std::filesystem::remove_all(folder);
  return 0;
}
