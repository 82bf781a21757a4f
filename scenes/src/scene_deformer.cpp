#include "ffdkit/scenes/scene_deformer.h"

#include <algorithm>
#include <chrono>
#include <set>
#include <stdexcept>

#include "ffdkit/ffd/control_weights.h"
#include "ffdkit/ffd/pipeline.h"

namespace ffdkit::scenes {
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

}  // namespace

struct SceneDeformer::ObjectPipeline {
  // The object's own points when the pipeline was built live in pipeline->inputPoints(); these
  // tell whether the object still holds them without comparing a million points per step.
  const double* meshData = nullptr;
  Eigen::Index meshRows = -1;
  std::uint64_t meshRevision = 0;
  std::vector<Stage> stages;
  std::unique_ptr<ffd::Pipeline> pipeline;
  std::map<widgets::WidgetId, ffd::LatticeId> ids;
  // Per stage: the model revisions its lattice in the pipeline was last synced to.
  std::map<widgets::WidgetId, std::pair<std::uint64_t, std::uint64_t>> synced;  // (frame, control)
  std::uint64_t revision = 0;  // of the output points (SceneDeformer::revision)
  // The base of gestureMotion(): the revision of the output that the last stage's delta steps
  // started from and that stage's (local) control points then; baseControl is empty when the
  // output changed otherwise since (no motion to follow).
  std::uint64_t baseRevision = 0;
  Eigen::MatrixX3d baseControl;
  bool moved = false;  // a delta step of the last stage ran since the base

  // Whether the object still holds the points this pipeline was built from.
  bool holdsSameMesh(const SceneObject& object) const;
  // A new pipeline for `stages` over the object's points (or the points taken from `takeFrom`):
  // a new object, new points or a new lattice tree. Returns the lattices built.
  int rebuild(const Scene& scene, const SceneObject& object, std::vector<Stage> stages, Scene* takeFrom);
  // The scene's lattices synced into the pipeline in place: a stage whose revisions did not move
  // is left alone; new control points are written into its lattice (updated incrementally), a
  // new frame moves it (re-embedding per the throttle); only a new rest shape makes a new
  // lattice. Returns the lattices built.
  int syncInPlace(const Scene& scene, const std::vector<Stage>& stages, bool sameModel);
  // What the object holds now (no points, when the pipeline took them over), to recognise it next time.
  void remember(const SceneObject& object);
  // After a pipeline run: the revision, and the base of gestureMotion() (see baseRevision).
  void recordRun();
};

bool SceneDeformer::ObjectPipeline::holdsSameMesh(const SceneObject& object) const {
  const Eigen::MatrixX3d& own = object.mesh.points;
  return pipeline && object.meshRevision == meshRevision && own.data() == meshData && own.rows() == meshRows;
}

int SceneDeformer::ObjectPipeline::rebuild(const Scene& scene, const SceneObject& object, std::vector<Stage> newStages,
                                           Scene* takeFrom) {
  auto built = takeFrom ? std::make_unique<ffd::Pipeline>(ffd::Pipeline::adopting(takeFrom->takeObjectPoints(object.name)))
                        : std::make_unique<ffd::Pipeline>(object.mesh.points);
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
  ++revision;
  baseControl.resize(0, 3);  // the next run sets the base (it embeds every stage)
  moved = false;
  return latticesBuilt;
}

int SceneDeformer::ObjectPipeline::syncInPlace(const Scene& scene, const std::vector<Stage>& current, bool sameModel) {
  int latticesBuilt = 0;
  for (const Stage& stage : current) {
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
  return latticesBuilt;
}

void SceneDeformer::ObjectPipeline::remember(const SceneObject& object) {
  meshData = object.mesh.points.data();
  meshRows = object.mesh.points.rows();
  meshRevision = object.meshRevision;
}

void SceneDeformer::ObjectPipeline::recordRun() {
  const std::vector<ffd::StageReport>& reports = pipeline->lastReport();
  const auto changedOutput = [](const ffd::StageReport& r) { return r.outputChanged; };
  if (!std::any_of(reports.begin(), reports.end(), changedOutput)) return;
  ++revision;
  // Only the last stage changed, by deltas: the output moved linearly in its control points
  // since the base. Anything else makes this output the new base.
  const bool lastByDelta = reports.back().delta && std::none_of(reports.begin(), reports.end() - 1, changedOutput);
  if (!lastByDelta || baseControl.size() == 0) {
    baseRevision = revision;
    baseControl = pipeline->lattice(reports.back().id).controlPoints();
    moved = false;
    if (lastByDelta) baseControl.resize(0, 3);  // moved from an unknown base: nothing to follow
  } else {
    moved = true;
  }
}

SceneDeformer::SceneDeformer() = default;
SceneDeformer::~SceneDeformer() = default;
SceneDeformer::SceneDeformer(SceneDeformer&&) noexcept = default;
SceneDeformer& SceneDeformer::operator=(SceneDeformer&&) noexcept = default;

void SceneDeformer::reset() {
  objects_.clear();
  evaluated_ = nullptr;
}

void SceneDeformer::beginGesture(std::optional<widgets::WidgetId> activeLattice) {
  gesture_ = true;
  gestureLattice_ = activeLattice;
}

void SceneDeformer::endGesture() {
  gesture_ = false;
  gestureLattice_.reset();
}

bool SceneDeformer::evaluate(const Scene& scene) {
  // Nothing changed since the last run, which already gave what the gesture state asks for.
  if (&scene == evaluated_ && markOf(scene) == evaluatedMark_ && (gesture_ || exact_)) return false;
  if (gesture_) {
    run(scene, gestureLattice_, Run::Gesture);
  } else {
    run(scene, std::nullopt, Run::Finish);
  }
  return true;
}

void SceneDeformer::evaluateTakingPoints(Scene& scene) { run(scene, std::nullopt, Run::Finish, &scene); }

void SceneDeformer::update(const Scene& scene, std::optional<widgets::WidgetId> activeLattice) {
  run(scene, activeLattice, Run::Update);
}

void SceneDeformer::updateGesture(const Scene& scene, std::optional<widgets::WidgetId> activeLattice) {
  run(scene, activeLattice, Run::Gesture);
}

void SceneDeformer::finishGesture(const Scene& scene) { run(scene, std::nullopt, Run::Finish); }

void SceneDeformer::finishGestureTakingPoints(Scene& scene) { run(scene, std::nullopt, Run::Finish, &scene); }

void SceneDeformer::run(const Scene& scene, std::optional<widgets::WidgetId> activeLattice, Run how,
                        Scene* takeFrom) {
  const bool exact = how == Run::Finish;
  const auto start = std::chrono::steady_clock::now();
  // 1. Sync every object's pipeline with the scene, in place (nothing is embedded yet), so that a
  //    throw in step 2 leaves each pipeline whole.
  std::vector<ObjectPipeline*> toRun;
  std::set<ObjectId> present;
  labels_.clear();
  // Revisions compare within one widget model: another instance (a replaced model) syncs in full.
  const bool sameModel = widgetInstance_ == scene.widgets.instance();
  int latticesBuilt = 0;
  for (const auto& object : scene.objects()) {
    present.insert(object.id);
    labels_.emplace(object.name, object.id);
    auto found = objects_.find(object.id);
    std::unique_ptr<ObjectPipeline> added;  // a new object enters objects_ once it is synced
    ObjectPipeline* p = found != objects_.end() ? found->second.get() : (added = std::make_unique<ObjectPipeline>()).get();
    std::vector<Stage> stages = stagesFor(scene, object.id);
    const Eigen::MatrixX3d& own = object.mesh.points;
    // A mesh at another address (a copied scene, an undo of an object edit) may still be the same:
    // compare it then, once, rather than rebuild.
    const bool inputChanged = !p->holdsSameMesh(object) &&
                              (!p->pipeline || p->pipeline->inputPoints().rows() != own.rows() || p->pipeline->inputPoints() != own);
    if (!p->pipeline || inputChanged || stages != p->stages) {
      latticesBuilt += p->rebuild(scene, object, std::move(stages), takeFrom);
    } else {
      latticesBuilt += p->syncInPlace(scene, stages, sameModel);
    }
    p->remember(object);
    if (!p->stages.empty()) {
      p->pipeline->setThrottle(throttleFor(scene.widgets.latticeSettings(p->stages.front().lattice)));
      std::optional<ffd::LatticeId> active;
      if (activeLattice && p->ids.count(*activeLattice)) active = p->ids.at(*activeLattice);
      p->pipeline->setActiveLattice(active);
      p->pipeline->setUpdateMode(how == Run::Gesture ? ffd::UpdateMode::Delta : ffd::UpdateMode::Exact);
      p->pipeline->setPrecision(precision_);
      toRun.push_back(p);
    }
    if (added) objects_[object.id] = std::move(added);
  }
  std::erase_if(objects_, [&present](const auto& entry) { return !present.count(entry.first); });
  widgetInstance_ = scene.widgets.instance();  // every object is synced to it

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
  stats.latticesBuilt = latticesBuilt;
  // An object's points, and those of them its first stage left outside or failed to embed.
  const auto countPoints = [&stats](const ObjectPipeline& p) {
    stats.deformedPoints += p.pipeline->inputPoints().rows();
    if (const ffd::Embedding* first = p.pipeline->embedding(p.ids.at(p.stages.front().lattice))) {
      stats.outsidePoints += first->outsideCount();
      stats.failedPoints += first->failedCount();
    }
  };
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
      stats.deltaStages += report.delta ? 1 : 0;
      stats.embedSeconds += report.embedSeconds;
    }
    countPoints(p);
    p.recordRun();
  }
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats_ = stats;
  evaluated_ = takeFrom != nullptr ? nullptr : &scene;  // points taken over: evaluate anew
  evaluatedMark_ = markOf(scene);
  exact_ = how == Run::Finish;
  totals_.reembeddedStages += std::uint64_t(stats.reembeddedStages);
  totals_.latticesBuilt += std::uint64_t(stats.latticesBuilt);
  ++totals_.evaluations;
  if (progress_ && !progress_(1.0)) throw ffd::Cancelled("scene deformer: cancelled at the end (all work kept)");
}

SceneDeformer::ObjectPipeline& SceneDeformer::pipelineOf(ObjectId object) const {
  auto it = objects_.find(object);
  if (it == objects_.end()) throw std::invalid_argument("SceneDeformer: unknown object " + toString(object));
  return *it->second;
}

ObjectId SceneDeformer::idOf(const std::string& object) const {
  auto it = labels_.find(object);
  if (it == labels_.end()) throw std::invalid_argument("SceneDeformer: unknown object '" + object + "'");
  return it->second;
}

const Eigen::MatrixX3d& SceneDeformer::points(const std::string& object) const { return points(idOf(object)); }
Eigen::MatrixX3d SceneDeformer::takePoints(const std::string& object) { return takePoints(idOf(object)); }
Eigen::Index SceneDeformer::pointCount(const std::string& object) const { return pointCount(idOf(object)); }
std::uint64_t SceneDeformer::revision(const std::string& object) const { return revision(idOf(object)); }
std::optional<GestureMotion> SceneDeformer::gestureMotion(const std::string& object) const {
  auto it = labels_.find(object);
  return it != labels_.end() ? gestureMotion(it->second) : std::nullopt;
}
Eigen::VectorXd SceneDeformer::controlWeights(const std::string& object, Eigen::Index controlPoint) const {
  return controlWeights(idOf(object), controlPoint);
}

const Eigen::MatrixX3d& SceneDeformer::points(ObjectId object) const {
  return pipelineOf(object).pipeline->points();
}

Eigen::MatrixX3d SceneDeformer::takePoints(ObjectId object) {
  (void)pipelineOf(object);  // throws for an unknown object
  evaluated_ = nullptr;  // the object is forgotten: the next evaluate() builds its pipeline again
  return objects_.extract(object).mapped()->pipeline->takePoints();
}

Eigen::Index SceneDeformer::pointCount(ObjectId object) const {
  return pipelineOf(object).pipeline->inputPoints().rows();
}

std::uint64_t SceneDeformer::revision(ObjectId object) const {
  return pipelineOf(object).revision;
}

std::optional<GestureMotion> SceneDeformer::gestureMotion(ObjectId object) const {
  auto it = objects_.find(object);
  if (it == objects_.end()) return std::nullopt;
  const ObjectPipeline& p = *it->second;
  if (!p.moved || p.baseControl.size() == 0 || p.stages.empty()) return std::nullopt;
  const ffd::LatticeId last = p.pipeline->order().back();
  const ffd::Lattice& lattice = p.pipeline->lattice(last);
  if (lattice.controlPoints().rows() != p.baseControl.rows()) return std::nullopt;
  if (lattice.isRational()) return std::nullopt;  // with weights the map is a ratio, not linear in the points
  GestureMotion motion;
  motion.baseRevision = p.baseRevision;
  for (const auto& [widget, id] : p.ids)
    if (id == last) motion.lattice = widget;
  std::vector<Eigen::Vector3d> moves;
  for (Eigen::Index f = 0; f < lattice.controlPoints().rows(); ++f) {
    if (lattice.controlPoints().row(f) == p.baseControl.row(f)) continue;
    motion.controlPoints.push_back(f);
    moves.push_back(lattice.frame().linear() * (lattice.controlPoints().row(f) - p.baseControl.row(f)).transpose());
  }
  motion.displacements.resize(static_cast<Eigen::Index>(moves.size()), 3);
  for (std::size_t c = 0; c < moves.size(); ++c) motion.displacements.row(static_cast<Eigen::Index>(c)) = moves[c].transpose();
  return motion;
}

Eigen::VectorXd SceneDeformer::controlWeights(ObjectId object, Eigen::Index controlPoint) const {
  Eigen::VectorXd weights;
  controlWeights(object, controlPoint, weights);
  return weights;
}

void SceneDeformer::controlWeights(ObjectId object, Eigen::Index controlPoint, Eigen::VectorXd& weights) const {
  const ObjectPipeline& p = pipelineOf(object);
  if (p.stages.empty()) throw std::invalid_argument("SceneDeformer: object " + toString(object) + " has no lattice");
  const ffd::LatticeId last = p.pipeline->order().back();
  const ffd::Embedding* embedding = p.pipeline->embedding(last);
  if (!embedding) throw std::invalid_argument("SceneDeformer: object " + toString(object) + " is not embedded yet");
  ffd::controlPointWeights(p.pipeline->lattice(last), *embedding, controlPoint, weights);
}

std::map<std::string, Eigen::MatrixX3d> deformScene(const Scene& scene) {
  SceneDeformer deformer;
  deformer.finishGesture(scene);  // the exact result in one pass
  std::map<std::string, Eigen::MatrixX3d> result;
  for (const auto& object : scene.objects()) result[object.name] = deformer.takePoints(object.id);
  return result;
}

}  // namespace ffdkit::scenes
