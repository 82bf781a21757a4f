// The installed cad component: a sample part deformed exactly by a lattice that stretches x by 2
// (an affine FFD, so the volume doubles), written as STEP into the folder given, read back,
// checked; and a file that is not STEP refused with a CadError naming it.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "../consumer_check.h"
#include "ffdkit/cad/cad_check.h"
#include "ffdkit/cad/cad_deform.h"
#include "ffdkit/cad/cad_error.h"
#include "ffdkit/cad/cad_io.h"
#include "ffdkit/cad/sample_parts.h"
#include "ffdkit/ffd/lattice.h"

int main(int argc, char** argv) {
  using namespace ffdkit;
  using consumer::check;
  if (argc != 2) return 2;
  const std::filesystem::path folder = argv[1];
  std::filesystem::create_directories(folder);

  const cad::CadModel part = cad::makeSamplePart(cad::SamplePart::FilletedBox);
  const Eigen::AlignedBox3d box = part.bounds();
  ffd::BoxLatticeOptions options;
  options.counts = Eigen::Vector3i(3, 3, 3);
  options.bases = {ffd::AxisBasis::bernstein(), ffd::AxisBasis::bernstein(), ffd::AxisBasis::bernstein()};
  options.boxMin = box.min() - Eigen::Vector3d::Constant(1.0);
  options.boxMax = box.max() + Eigen::Vector3d::Constant(1.0);
  ffd::Lattice lattice = ffd::makeBoxLattice(options);
  Eigen::MatrixX3d points = lattice.controlPoints();
  const double x0 = options.boxMin.x();
  points.col(0) = (points.col(0).array() - x0) * 2.0 + x0;  // x stretched by 2 about the box's side
  lattice.setControlPoints(points);

  const cad::CadDeformResult deformed = cad::deformCad(part, lattice);
  const std::filesystem::path path = folder / "stretched.step";
  cad::writeStep(deformed.model, path);
  const cad::CadModel back = cad::readStep(path);
  const cad::CadCheck original = cad::checkModel(part);
  const cad::CadCheck result = cad::checkModel(back);
  check(result.valid, "the stretched part read back from STEP passes BRepCheck");
  check(std::abs(result.volume - 2.0 * original.volume) < 1e-7 * original.volume, "its volume is twice the part's");
  check(std::abs(back.bounds().sizes().x() - 2.0 * box.sizes().x()) < 1e-6 * box.sizes().x(), "its width is twice the part's");

  const std::filesystem::path bad = folder / "not-a-part.step";
  std::ofstream(bad) << "this is not STEP\n";
  bool refused = false;
  try {
    cad::readStep(bad);
  } catch (const cad::CadError& e) {
    refused = std::string(e.what()).find("not-a-part.step") != std::string::npos;
  }
  check(refused, "a file that is not STEP is a CadError naming it");
  return consumer::exitCode();
}
