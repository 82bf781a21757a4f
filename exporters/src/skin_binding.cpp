#include "ffdkit/exporters/skin_binding.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "ffdkit/ffd/control_weights.h"
#include "ffdkit/ffd/deformer.h"

namespace ffdkit::exporters {
namespace {

std::string jointName(const std::string& lattice, const Eigen::Vector3i& g) {
  return lattice + "[" + std::to_string(g.x()) + "," + std::to_string(g.y()) + "," + std::to_string(g.z()) + "]";
}

}  // namespace

SkinBinding bindSkin(const scenes::Scene& bind, int maxJoints) {
  if (maxJoints < 1) throw std::invalid_argument("bindSkin: maxJoints must be >= 1, got " + std::to_string(maxJoints));
  SkinBinding binding;
  binding.maxJoints = maxJoints;
  binding.joints.push_back({"rest", {}, -1, Eigen::Vector3d::Zero()});
  // Joints: every lattice deforming some object, in the scene's pipeline order.
  for (const widgets::WidgetId lattice : bind.widgets.pipelineOrder()) {
    bool used = false;
    for (const auto& object : bind.objects()) {
      const auto stages = bind.stagesDeforming(object.name);
      used = used || std::find(stages.begin(), stages.end(), lattice) != stages.end();
    }
    if (!used) continue;
    binding.firstJoint[lattice] = static_cast<int>(binding.joints.size());
    const ffd::Lattice ffdLattice = bind.widgets.ffdLattice(lattice);
    const Eigen::MatrixX3d rest = bind.widgets.worldRestPoints(lattice);
    for (Eigen::Index f = 0; f < ffdLattice.pointCount(); ++f)
      binding.joints.push_back({jointName(bind.widgets.name(lattice), ffdLattice.gridIndex(f)), lattice, f,
                                rest.row(f).transpose()});
  }

  // Pass 1: embed Q in every stage's bind-state rest lattice; the largest weights per stage.
  struct Pending {
    std::vector<ffd::ControlWeights> perStage;
    Eigen::VectorXd total;  // sum over stages of s
  };
  std::vector<Pending> pending;
  for (const auto& object : bind.objects()) {
    const std::vector<widgets::WidgetId> stages = bind.stagesDeforming(object.name);
    if (stages.empty()) continue;
    ObjectSkin skin;
    skin.object = object.name;
    skin.stages = stages;
    Pending p;
    p.total = Eigen::VectorXd::Zero(object.mesh.points.rows());
    for (const widgets::WidgetId stage : stages) {
      const ffd::Lattice lattice = bind.widgets.ffdLattice(stage);
      skin.deformers.emplace_back(ffd::embed(lattice, object.mesh.points));
      p.perStage.push_back(ffd::largestControlWeights(lattice, skin.deformers.back().embedding(), maxJoints));
      p.total += p.perStage.back().total;
    }
    if (p.total.size() > 0) binding.jointScale = std::max(binding.jointScale, p.total.maxCoeff());
    binding.objects.push_back(std::move(skin));
    pending.push_back(std::move(p));
  }

  // Pass 2: per vertex the candidates of every stage (the k largest of the union are among the
  // k largest of each stage) and the static joint, scaled by c, the largest kMax kept.
  const double c = binding.jointScale;
  struct Candidate {
    std::int32_t joint;
    double weight;
  };
  for (std::size_t o = 0; o < binding.objects.size(); ++o) {
    ObjectSkin& skin = binding.objects[o];
    const Pending& p = pending[o];
    const Eigen::Index n = p.total.size();
    skin.joints.setZero(n, maxJoints);
    skin.weights.setZero(n, maxJoints);
#pragma omp parallel if (n >= 16384)
    {
      std::vector<Candidate> candidates;
#pragma omp for schedule(static)
      for (Eigen::Index v = 0; v < n; ++v) {
        candidates.clear();
        for (std::size_t st = 0; st < skin.stages.size(); ++st) {
          const ffd::ControlWeights& cw = p.perStage[st];
          const int first = binding.firstJoint.at(skin.stages[st]);
          for (int r = 0; r < maxJoints; ++r)
            if (cw.indices(v, r) >= 0) candidates.push_back({first + cw.indices(v, r), cw.weights(v, r) / c});
        }
        candidates.push_back({0, 1.0 - p.total[v] / c});
        // Largest first; ties keep the stage / window order (deterministic).
        std::stable_sort(candidates.begin(), candidates.end(),
                         [](const Candidate& a, const Candidate& b) { return a.weight > b.weight; });
        const int kept = std::min<int>(maxJoints, static_cast<int>(candidates.size()));
        for (int r = 0; r < kept; ++r) {
          skin.joints(v, r) = candidates[std::size_t(r)].joint;
          skin.weights(v, r) = candidates[std::size_t(r)].weight;
        }
      }
    }
  }
  return binding;
}

Eigen::MatrixX3d jointTranslations(const SkinBinding& binding, const scenes::Scene& scene) {
  Eigen::MatrixX3d t(static_cast<Eigen::Index>(binding.joints.size()), 3);
  t.row(0).setZero();
  for (const auto& [lattice, first] : binding.firstJoint) {
    // D = F.linear() (P - Pbar): the world displacement Deformer applies (deformer.h).
    const Eigen::MatrixX3d D = (scene.widgets.controlPoints(lattice) - scene.widgets.restPoints(lattice)) *
                               scene.widgets.latticeFrame(lattice).linear().transpose();
    for (Eigen::Index f = 0; f < D.rows(); ++f) {
      const SkinJoint& joint = binding.joints[std::size_t(first + f)];
      t.row(first + f) = joint.bindPosition.transpose() + binding.jointScale * D.row(f);
    }
  }
  return t;
}

PrunedSkin pruneSkin(const ObjectSkin& skin, int k) {
  if (k < 1 || k > skin.weights.cols())
    throw std::invalid_argument("pruneSkin: k must be in [1, " + std::to_string(skin.weights.cols()) + "], got " +
                                std::to_string(k));
  const Eigen::Index n = skin.weights.rows();
  PrunedSkin pruned;
  pruned.k = k;
  pruned.joints.setZero(n, k);
  pruned.weights.setZero(n, k);
  for (Eigen::Index v = 0; v < n; ++v) {
    double sum = 0.0;
    for (int r = 0; r < k; ++r) sum += std::max(0.0, skin.weights(v, r));
    // sum > 0: the weights sum to 1, so the largest is >= 1 / window > 0.
    int largest = 0;
    float floatSum = 0.0f;
    for (int r = 0; r < k; ++r) {
      const double w = std::max(0.0, skin.weights(v, r)) / sum;
      pruned.joints(v, r) = w > 0.0 ? static_cast<std::uint16_t>(skin.joints(v, r)) : 0;
      pruned.weights(v, r) = static_cast<float>(w);
      if (pruned.weights(v, r) > pruned.weights(v, largest)) largest = r;
    }
    for (int r = 0; r < k; ++r)
      if (r != largest) floatSum += pruned.weights(v, r);
    pruned.weights(v, largest) = 1.0f - floatSum;
  }
  return pruned;
}

Eigen::MatrixX3d skinnedPositions(const Eigen::MatrixX3d& rest, const PrunedSkin& skin,
                                  const Eigen::MatrixX3d& nodeTranslations,
                                  const Eigen::MatrixX3d& inverseBindTranslations) {
  const Eigen::MatrixX3d jointShift = nodeTranslations + inverseBindTranslations;
  Eigen::MatrixX3d out(rest.rows(), 3);
#pragma omp parallel for schedule(static) if (rest.rows() >= 16384)
  for (Eigen::Index v = 0; v < rest.rows(); ++v) {
    Eigen::RowVector3d x = Eigen::RowVector3d::Zero();
    for (int r = 0; r < skin.k; ++r) {
      const double w = skin.weights(v, r);
      if (w != 0.0f) x += w * (rest.row(v) + jointShift.row(skin.joints(v, r)));
    }
    out.row(v) = x;
  }
  return out;
}

Eigen::MatrixX3d linearPositions(const ObjectSkin& skin, const scenes::Scene& scene) {
  const scenes::SceneObject* object = scene.findObject(skin.object);
  if (!object) throw std::invalid_argument("linearPositions: no object '" + skin.object + "' in the scene");
  const Eigen::MatrixX3d& Q = object->mesh.points;
  Eigen::MatrixX3d out = Q;
  for (std::size_t st = 0; st < skin.stages.size(); ++st) {
    out += skin.deformers[st].deformStale(scene.widgets.ffdLattice(skin.stages[st]), Q) - Q;
  }
  return out;
}

Eigen::MatrixX3d roundToFloat(const Eigen::MatrixX3d& values) { return values.cast<float>().cast<double>(); }

}  // namespace ffdkit::exporters
