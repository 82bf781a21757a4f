#include "stage_pipeline.h"

#include <algorithm>

namespace ffdkit::scenes::detail {
namespace {

bool sameBasis(const ffd::AxisBasis& a, const ffd::AxisBasis& b) {
  return a.kind == b.kind && a.degree == b.degree && a.knots.size() == b.knots.size() && a.knots == b.knots;
}

// True when the pipeline's `current` lattice has the model lattice's rest shape (counts, rest
// points, bases, outside policy): then a new frame moves it in place (Lattice::setFrame) and an
// edit of control points needs no new lattice. Read only after the lattice's frame revision moved.
bool sameRestShape(const widgets::WidgetModel& model, widgets::WidgetId id, const ffd::Lattice& current) {
  const widgets::LatticeSettings& settings = model.latticeSettings(id);
  if (model.counts(id) != current.counts() || !(settings.outside == current.outsidePolicy()) ||
      model.restPoints(id) != current.restPoints())
    return false;
  for (int axis = 0; axis < 3; ++axis)
    if (!sameBasis(settings.basis[std::size_t(axis)], current.basis(axis))) return false;
  return true;
}

}  // namespace

ffd::ReembedThrottle throttleFor(const widgets::LatticeSettings& settings) {
  switch (settings.reembed.kind) {
    case widgets::ReembedKind::Immediate: return ffd::ReembedThrottle::immediate();
    case widgets::ReembedKind::EveryN: return ffd::ReembedThrottle::everyN(settings.reembed.everyN);
    case widgets::ReembedKind::OnRelease: return ffd::ReembedThrottle::onDemand();
  }
  return ffd::ReembedThrottle::immediate();
}

std::vector<Stage> stagesFor(const Scene& scene, ObjectId object) {
  std::vector<Stage> stages;
  int rootPriority = 0;
  for (widgets::WidgetId lattice : scene.stagesDeforming(object)) {
    const std::optional<widgets::WidgetId> parent = scene.widgets.parentLattice(lattice);
    int priority = rootPriority;
    if (parent) {
      const std::vector<widgets::WidgetId> siblings = scene.widgets.children(*parent);
      priority = static_cast<int>(std::find(siblings.begin(), siblings.end(), lattice) - siblings.begin());
    } else {
      ++rootPriority;
    }
    stages.push_back({lattice, parent, priority});
  }
  return stages;
}

int StagePipeline::build(const Scene& scene, std::unique_ptr<ffd::Pipeline> built, std::vector<Stage> newStages) {
  std::map<widgets::WidgetId, ffd::LatticeId> newIds;
  int latticesBuilt = 0;
  synced.clear();
  for (const Stage& stage : newStages) {
    std::optional<ffd::LatticeId> parent;
    if (stage.parent) parent = newIds.at(*stage.parent);
    newIds[stage.lattice] = built->addLattice(scene.widgets.ffdLattice(stage.lattice), parent, stage.priority);
    ++latticesBuilt;
    synced[stage.lattice] = {scene.widgets.frameRevision(stage.lattice), scene.widgets.controlRevision(stage.lattice)};
  }
  stages = std::move(newStages);
  pipeline = std::move(built);
  ids = std::move(newIds);
  modelInstance = scene.widgets.instance();
  return latticesBuilt;
}

int StagePipeline::sync(const Scene& scene) {
  // Revisions compare within one widget model: another instance (a replaced model) syncs in full.
  const bool sameModel = modelInstance == scene.widgets.instance();
  int latticesBuilt = 0;
  for (const Stage& stage : stages) {
    const std::uint64_t frameRevision = scene.widgets.frameRevision(stage.lattice);
    const std::uint64_t controlRevision = scene.widgets.controlRevision(stage.lattice);
    auto& seen = synced[stage.lattice];
    if (sameModel && seen == std::pair(frameRevision, controlRevision)) continue;
    ffd::Lattice& lattice = pipeline->lattice(ids.at(stage.lattice));
    if (!sameModel || seen.first != frameRevision) {
      if (!sameRestShape(scene.widgets, stage.lattice, lattice)) {
        lattice = scene.widgets.ffdLattice(stage.lattice);
        ++latticesBuilt;
      } else if (const Eigen::Affine3d frame = scene.widgets.latticeFrame(stage.lattice);
                 frame.matrix() != lattice.frame().matrix()) {
        lattice.setFrame(frame);
      }
    }
    const Eigen::MatrixX3d& control = scene.widgets.controlPoints(stage.lattice);
    if (control != lattice.controlPoints()) lattice.setControlPoints(control);
    if (const Eigen::VectorXd weights = scene.widgets.weights(stage.lattice); weights != lattice.weights())
      lattice.setWeights(weights);
    seen = {frameRevision, controlRevision};
  }
  modelInstance = scene.widgets.instance();
  return latticesBuilt;
}

void StagePipeline::prepareRun(const Scene& scene, std::optional<widgets::WidgetId> activeLattice, ffd::UpdateMode mode,
                               ffd::Precision precision) {
  pipeline->setThrottle(throttleFor(scene.widgets.latticeSettings(stages.front().lattice)));
  std::optional<ffd::LatticeId> active;
  if (activeLattice && ids.count(*activeLattice)) active = ids.at(*activeLattice);
  pipeline->setActiveLattice(active);
  pipeline->setUpdateMode(mode);
  pipeline->setPrecision(precision);
}

}  // namespace ffdkit::scenes::detail
