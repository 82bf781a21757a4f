#include "outward_faces.h"

#include <algorithm>
#include <array>

#include "ffdkit/ffd/fold_check.h"
#include "ffdkit/ffd/lattice.h"

namespace ffdkit::app {

const OutwardFacesGuard::LatticeVerdict& OutwardFacesGuard::verdict(const widgets::WidgetModel& model,
                                                                    widgets::WidgetId lattice,
                                                                    const std::vector<CertifiedLattice>& certified) {
  const std::uint64_t control = model.controlRevision(lattice), frame = model.frameRevision(lattice);
  auto [at, added] = verdicts_.try_emplace(lattice);
  LatticeVerdict& v = at->second;
  if (!added && v.controlRevision == control && v.frameRevision == frame) return v;
  v = LatticeVerdict{};
  v.controlRevision = control;
  v.frameRevision = frame;
  if (model.parentLattice(lattice)) return v;
  try {
    const ffd::Lattice l = model.ffdLattice(lattice);
    v.identityOutside = l.outsidePolicy().kind == ffd::OutsidePolicy::Kind::Identity;
    if (!l.restIsAffine()) return v;
    // world = frame * local, local rest = A uvw + b (Lattice::restAffineLinear / Offset).
    Eigen::Affine3d parametersToWorld = l.frame();
    parametersToWorld.linear() = l.frame().linear() * l.restAffineLinear();
    parametersToWorld.translation() = l.frame() * l.restAffineOffset();
    v.worldToParameters = parametersToWorld.inverse();
    v.parameterMin = l.parameterMin();
    v.parameterMax = l.parameterMax();
    v.affineRoot = true;
    if (std::find(certified.begin(), certified.end(), CertifiedLattice{lattice, control, frame}) != certified.end()) {
      v.certified = true;  // a controller's check of these very revisions
      return v;
    }
    ++checks_;
    v.certified = ffd::checkFolding(l).certifiedPositive();
  } catch (const std::exception&) {
    v = LatticeVerdict{control, frame};  // a lattice the check cannot bound keeps nothing
  }
  return v;
}

bool OutwardFacesGuard::keepsOutward(const widgets::WidgetModel& model, const Eigen::Vector3d& lo,
                                     const Eigen::Vector3d& hi, const std::vector<CertifiedLattice>& certified) {
  if (model.instance() != instance_) {  // another model: its ids name other lattices
    verdicts_.clear();
    instance_ = model.instance();
  }
  const std::vector<widgets::WidgetId> lattices = model.widgets(widgets::WidgetType::Lattice);
  std::erase_if(verdicts_, [&](const auto& entry) { return !model.contains(entry.first); });
  for (widgets::WidgetId lattice : lattices) {
    const LatticeVerdict& v = verdict(model, lattice, certified);
    if (!v.affineRoot) return false;
    // The box's corners in the lattice's parameters: the box is their convex hull, and so is its
    // image under the affine rest map's inverse, so the corners decide inside and outside.
    const Eigen::Vector3d slack = 1e-9 * (v.parameterMax - v.parameterMin);
    bool allInside = true;
    std::array<bool, 6> allBeyond{true, true, true, true, true, true};  // below / above each axis
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d p(corner & 1 ? hi.x() : lo.x(), corner & 2 ? hi.y() : lo.y(), corner & 4 ? hi.z() : lo.z());
      const Eigen::Vector3d uvw = v.worldToParameters * p;
      for (int a = 0; a < 3; ++a) {
        const bool below = uvw[a] < v.parameterMin[a] - slack[a], above = uvw[a] > v.parameterMax[a] + slack[a];
        if (!(uvw[a] >= v.parameterMin[a] - slack[a] && uvw[a] <= v.parameterMax[a] + slack[a]))
          allInside = false;  // written so that a NaN is neither inside nor beyond
        if (!below) allBeyond[2 * a] = false;
        if (!above) allBeyond[2 * a + 1] = false;
      }
    }
    const bool outside = std::find(allBeyond.begin(), allBeyond.end(), true) != allBeyond.end();
    if (allInside ? !v.certified : !(outside && v.identityOutside)) return false;
  }
  return true;
}

}  // namespace ffdkit::app
