#include "ffdkit/geometry/curvenet/curve_network_surface.h"

#include <stdexcept>
#include <string>

namespace ffdkit::geometry::curvenet {

void CurveNetworkSurfaceParams::validate() const {
  if (network.curves.size() < 2) {
    throw std::invalid_argument("curve-network-surface: network.curves needs >= 2 curves, got " +
                                std::to_string(network.curves.size()));
  }
  if (networkOptions.intersectionTolerance < 0.0) {
    throw std::invalid_argument("curve-network-surface: networkOptions.intersectionTolerance must be >= 0 (0 = automatic), got " +
                                std::to_string(networkOptions.intersectionTolerance));
  }
  if (!(networkOptions.minimumCrossingAngleDegrees > 0.0 && networkOptions.minimumCrossingAngleDegrees < 90.0)) {
    throw std::invalid_argument("curve-network-surface: networkOptions.minimumCrossingAngleDegrees must be in (0, 90), got " +
                                std::to_string(networkOptions.minimumCrossingAngleDegrees));
  }
  if (!(networkOptions.straightAngleDegrees > 0.0 && networkOptions.straightAngleDegrees < 90.0)) {
    throw std::invalid_argument("curve-network-surface: networkOptions.straightAngleDegrees must be in (0, 90), got " +
                                std::to_string(networkOptions.straightAngleDegrees));
  }
  if (patch.blendingExponent < 1 || patch.blendingExponent > 8) {
    throw std::invalid_argument("curve-network-surface: patch.blendingExponent must be in 1..8, got " +
                                std::to_string(patch.blendingExponent));
  }
}

NetworkMesh generateCurveNetworkSurfaceWithNormals(const CurveNetworkSurfaceParams& params, int pitch) {
  params.validate();
  if (pitch < 1) throw std::invalid_argument("curve-network-surface: pitch must be >= 1, got " + std::to_string(pitch));
  CurveNetwork network = buildCurveNetwork(params.network, params.networkOptions);
  if (params.fairing) fairRunSweeps(network);
  return tessellateNetwork(network, pitch, params.patch);
}

TriangleMesh generateCurveNetworkSurface(const CurveNetworkSurfaceParams& params, int pitch) {
  return generateCurveNetworkSurfaceWithNormals(params, pitch).mesh;
}

}  // namespace ffdkit::geometry::curvenet
