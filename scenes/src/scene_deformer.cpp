#include "ffdkit/scenes/scene_deformer.h"

#include <algorithm>
#include <chrono>
#include <set>
#include <stdexcept>

#include "ffdkit/ffd/pipeline.h"

namespace ffdkit::scenes {
namespace {

bool sameBasis(const ffd::AxisBasis& a, const ffd::AxisBasis& b) {
  return a.kind == b.kind && a.degree == b.degree && a.knots.size() == b.knots.size() && a.knots == b.knots;
}

// True when `a` and `b` have the same rest lattice in the world (counts, frame, rest points,
// bases, outside policy): then an edit of control points needs no new embedding.
bool sameRestLattice(const ffd::Lattice& a, const ffd::Lattice& b) {
  if (a.counts() != b.counts() || a.frame().matrix() != b.frame().matrix() || a.restPoints() != b.restPoints() ||
      !(a.outsidePolicy() == b.outsidePolicy()))
    return false;
  for (int axis = 0; axis < 3; ++axis)
    if (!sameBasis(a.basis(axis), b.basis(axis))) return false;
  return true;
}

ffd::ReembedThrottle throttleFor(const widgets::LatticeSettings& settings) {
  switch (settings.reembed.kind) {
    case widgets::ReembedKind::Immediate: return ffd::ReembedThrottle::immediate();
    case widgets::ReembedKind::EveryN: return ffd::ReembedThrottle::everyN(settings.reembed.everyN);
    case widgets::ReembedKind::OnRelease: return ffd::ReembedThrottle::onDemand();
  }
  return ffd::ReembedThrottle::immediate();
}

// The lattices deforming one object, in pipeline order, with their parents: the object's
// attached roots in attachment order, each followed by its subtree in pre-order.
struct Stage {
  widgets::WidgetId lattice;
  std::optional<widgets::WidgetId> parent;
  int priority = 0;
  bool operator==(const Stage&) const = default;
};

std::vector<Stage> stagesFor(const Scene& scene, const std::string& object) {
  std::vector<Stage> stages;
  int rootPriority = 0;
  for (widgets::WidgetId root : scene.latticesDeforming(object)) {
    std::vector<Stage> stack{{root, std::nullopt, rootPriority++}};
    while (!stack.empty()) {
      Stage stage = stack.back();
      stack.pop_back();
      stages.push_back(stage);
      const auto children = scene.widgets.children(stage.lattice);
      for (int c = static_cast<int>(children.size()) - 1; c >= 0; --c)
        stack.push_back({children[std::size_t(c)], stage.lattice, c});
    }
  }
  return stages;
}

}  // namespace

struct SceneDeformer::ObjectPipeline {
  Eigen::MatrixX3d input;  // the object's own points when the pipeline was built
  std::vector<Stage> stages;
  std::unique_ptr<ffd::Pipeline> pipeline;
  std::map<widgets::WidgetId, ffd::LatticeId> ids;
};

SceneDeformer::SceneDeformer() = default;
SceneDeformer::~SceneDeformer() = default;
SceneDeformer::SceneDeformer(SceneDeformer&&) noexcept = default;
SceneDeformer& SceneDeformer::operator=(SceneDeformer&&) noexcept = default;

void SceneDeformer::reset() { objects_.clear(); }

void SceneDeformer::update(const Scene& scene, std::optional<widgets::WidgetId> activeLattice) {
  run(scene, activeLattice, /*exact=*/false);
}

void SceneDeformer::finishGesture(const Scene& scene) { run(scene, std::nullopt, /*exact=*/true); }

void SceneDeformer::run(const Scene& scene, std::optional<widgets::WidgetId> activeLattice, bool exact) {
  const auto start = std::chrono::steady_clock::now();
  // 1. Sync every object's pipeline with the scene, in place (nothing is embedded yet), so that a
  //    throw in step 2 leaves each pipeline whole.
  std::vector<ObjectPipeline*> toRun;
  std::set<std::string> names;
  for (const auto& object : scene.objects) {
    names.insert(object.name);
    auto found = objects_.find(object.name);
    std::unique_ptr<ObjectPipeline> added;  // a new object enters objects_ once it is synced
    ObjectPipeline* p = found != objects_.end() ? found->second.get() : (added = std::make_unique<ObjectPipeline>()).get();
    std::vector<Stage> stages = stagesFor(scene, object.name);
    const bool inputChanged = p->input.rows() != object.mesh.points.rows() || p->input != object.mesh.points;
    if (!p->pipeline || inputChanged || stages != p->stages) {
      // New object, new points or a new lattice tree: rebuild (embeddings follow on update).
      auto pipeline = std::make_unique<ffd::Pipeline>(object.mesh.points);
      std::map<widgets::WidgetId, ffd::LatticeId> ids;
      for (const Stage& stage : stages) {
        std::optional<ffd::LatticeId> parent;
        if (stage.parent) parent = ids.at(*stage.parent);
        ids[stage.lattice] = pipeline->addLattice(scene.widgets.ffdLattice(stage.lattice), parent, stage.priority);
      }
      p->input = object.mesh.points;
      p->stages = std::move(stages);
      p->pipeline = std::move(pipeline);
      p->ids = std::move(ids);
    } else {
      for (const Stage& stage : stages) {
        ffd::Lattice fresh = scene.widgets.ffdLattice(stage.lattice);
        ffd::Lattice& current = p->pipeline->lattice(p->ids.at(stage.lattice));
        if (!sameRestLattice(fresh, current)) {
          current = std::move(fresh);  // its rest lattice moved: re-embed (per the throttle)
        } else if (fresh.controlPoints() != current.controlPoints()) {
          current.setControlPoints(fresh.controlPoints());  // an edit: incremental update
        }
      }
    }
    if (!p->stages.empty()) {
      p->pipeline->setThrottle(throttleFor(scene.widgets.latticeSettings(p->stages.front().lattice)));
      std::optional<ffd::LatticeId> active;
      if (activeLattice && p->ids.count(*activeLattice)) active = p->ids.at(*activeLattice);
      p->pipeline->setActiveLattice(active);
      toRun.push_back(p);
    }
    if (added) objects_[object.name] = std::move(added);
  }
  std::erase_if(objects_, [&names](const auto& entry) { return !names.count(entry.first); });

  // 2. Run the pipelines; progress counts the points every one of them embeds.
  std::vector<Eigen::Index> toEmbed;
  Eigen::Index total = 0;
  if (progress_) {
    for (const ObjectPipeline* p : toRun) total += toEmbed.emplace_back(p->pipeline->pointsToEmbed(exact));
  }
  const auto goOn = [this, total](Eigen::Index done) {
    return progress_(total > 0 ? double(std::min(done, total)) / double(total) : 0.0);
  };
  if (progress_ && !goOn(0)) throw ffd::Cancelled("scene deformer: cancelled before any embedding");
  SceneDeformStats stats;
  Eigen::Index done = 0;
  for (std::size_t i = 0; i < toRun.size(); ++i) {
    ObjectPipeline& p = *toRun[i];
    ffd::EmbedProgress hook;
    if (progress_ && toEmbed[i] > 0) hook = [&goOn, done](Eigen::Index d, Eigen::Index) { return goOn(done + d); };
    // exact: re-embed every throttled stage too (one pipeline pass, not an update and then another).
    if (exact) {
      p.pipeline->reembedAll(hook);
    } else {
      p.pipeline->update(hook);
    }
    if (progress_) done += toEmbed[i];
    for (const auto& report : p.pipeline->lastReport()) {
      stats.reembeddedStages += report.reembedded ? 1 : 0;
      stats.embedSeconds += report.embedSeconds;
    }
    if (const ffd::Embedding* first = p.pipeline->embedding(p.ids.at(p.stages.front().lattice))) {
      stats.outsidePoints += first->outsideCount();
      stats.failedPoints += first->failedCount();
    }
    stats.deformedPoints += p.input.rows();
  }
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats_ = stats;
  if (progress_ && !progress_(1.0)) throw ffd::Cancelled("scene deformer: cancelled at the end (all work kept)");
}

const Eigen::MatrixX3d& SceneDeformer::points(const std::string& object) const {
  auto it = objects_.find(object);
  if (it == objects_.end()) throw std::invalid_argument("SceneDeformer: unknown object '" + object + "'");
  const ObjectPipeline& p = *it->second;
  return p.stages.empty() ? p.input : p.pipeline->points();
}

std::map<std::string, Eigen::MatrixX3d> deformScene(const Scene& scene) {
  SceneDeformer deformer;
  deformer.finishGesture(scene);  // the exact result in one pass
  std::map<std::string, Eigen::MatrixX3d> result;
  for (const auto& object : scene.objects) result[object.name] = deformer.points(object.name);
  return result;
}

}  // namespace ffdkit::scenes
