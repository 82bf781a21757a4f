#pragma once

#include <string>
#include <vector>

#include "ffdkit/cad/cad_model.h"

namespace ffdkit::cad {

/// Parts built with OpenCASCADE's modelling API, for tests, benchmarks and the docs' table.
enum class SamplePart {
  FilletedBox,      ///< 60 x 40 x 30 box, every edge filleted (radius 5): planes, cylinders, spheres
  Blade,            ///< a twisted, tapering blade lofted through four airfoil-like B-spline sections
  BentPipe,         ///< a tube (radius 8, wall 2) swept along a line, a 90 degree arc and a line
  Bottle,           ///< OCCT's tutorial bottle (Make Bottle), 70 high
  TwoPartAssembly   ///< two named parts: a plate and a cylinder standing on it
};

/// Every sample part, in the order above.
std::vector<SamplePart> allSampleParts();
/// "filleted-box", "blade", "bent-pipe", "bottle", "two-part-assembly".
std::string samplePartName(SamplePart part);
/// Builds the part. @throws CadError if OpenCASCADE fails to build it.
CadModel makeSamplePart(SamplePart part);

}  // namespace ffdkit::cad
