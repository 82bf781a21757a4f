#include "ffdkit/scenes/scene_deformer.h"

#include <algorithm>
#include <chrono>
#include <set>
#include <span>
#include <string>
#include <stdexcept>

#include "ffdkit/ffd/control_weights.h"
#include "ffdkit/ffd/pipeline.h"
#include "stage_pipeline.h"

namespace ffdkit::scenes {

using detail::Stage;

struct SceneDeformer::ObjectPipeline {
  // The object's own points when the pipeline was built live in full.pipeline->inputPoints();
  // these tell whether the object still holds them without comparing a million points per step.
  const double* meshData = nullptr;
  Eigen::Index meshRows = -1;
  std::uint64_t meshRevision = 0;
  detail::StagePipeline full;  // over every point of the object
  // Over the points of a subset a request asked for during a gesture (EvaluationRequest): built
  // at the first such request and kept while the object's mesh, lattice tree and the subset stay,
  // so that the next gesture's first step embeds nothing. Null until then.
  struct Subset {
    std::vector<Eigen::Index> indices;
    detail::StagePipeline stages;
  };
  std::unique_ptr<Subset> subset;
  PointCoverage coverage = PointCoverage::Full;  // what the last run evaluated
  std::uint64_t revision = 0;  // of the evaluated points (SceneDeformer::revision)
  // The base of gestureMotion(): the revision of the output that the last stage's delta steps
  // started from and that stage's (local) control points then; baseControl is empty when the
  // output changed otherwise since (no motion to follow).
  std::uint64_t baseRevision = 0;
  Eigen::MatrixX3d baseControl;
  bool moved = false;  // a delta step of the last stage ran since the base
  // While moved: the one control point the motion since the base moved (-1: several or none) and
  // its displacement at the last step recorded (evaluated or waiting: PointCoverage::Motion).
  Eigen::Index movedControl = -1;
  Eigen::Vector3d movedBy = Eigen::Vector3d::Zero();

  // Whether the object still holds the points this pipeline was built from.
  bool holdsSameMesh(const SceneObject& object) const;
  // A new full pipeline for `stages` over the object's points (or the points taken from
  // `takeFrom`): a new object, new points or a new lattice tree. Returns the lattices built.
  int rebuild(const Scene& scene, const SceneObject& object, std::vector<Stage> stages, Scene* takeFrom);
  // The subset pipeline over `indices` of the full pipeline's input, built when there is none for
  // them, synced with the scene otherwise. Returns the lattices built.
  // @throws std::invalid_argument for indices not increasing or out of range.
  int prepareSubset(const Scene& scene, std::span<const Eigen::Index> indices);
  // What the object holds now (no points, when the pipeline took them over), to recognise it next time.
  void remember(const SceneObject& object);
  // After a run of the full pipeline: the revision, the coverage, and the base of gestureMotion().
  void recordRun();
  // After a run of the subset pipeline: the revision and the coverage (the full points wait).
  void recordSubsetRun();
  // Whether a gesture step of the full pipeline (synced, prepared by deltas) may wait for an
  // object its caller follows (EvaluationRequest::followed): the step moves only the last stage,
  // by deltas, and the motion since the base is still the one control point it was at the last
  // step. Then recordWaitingStep() records it instead of a run.
  bool mayWait() const;
  // A step that waits: the revision (when the control point moved since the last step) and the
  // coverage (PointCoverage::Motion); the base and the motion stay.
  void recordWaitingStep();
  // movedControl and movedBy from the motion since the base.
  void recordMotion();
  // The motion of the last stage's control points since the base (gestureMotion() without
  // asking whether a delta step ran since).
  std::optional<GestureMotion> motionSinceBase() const;
};

bool SceneDeformer::ObjectPipeline::holdsSameMesh(const SceneObject& object) const {
  const Eigen::MatrixX3d& own = object.mesh.points;
  return full.pipeline && object.meshRevision == meshRevision && own.data() == meshData && own.rows() == meshRows;
}

int SceneDeformer::ObjectPipeline::rebuild(const Scene& scene, const SceneObject& object, std::vector<Stage> newStages,
                                           Scene* takeFrom) {
  auto built = takeFrom ? std::make_unique<ffd::Pipeline>(ffd::Pipeline::adopting(takeFrom->takeObjectPoints(object.name)))
                        : std::make_unique<ffd::Pipeline>(object.mesh.points);
  const int latticesBuilt = full.build(scene, std::move(built), std::move(newStages));
  subset.reset();  // it was over the old points or lattice tree
  coverage = PointCoverage::Full;
  ++revision;
  baseControl.resize(0, 3);  // the next run sets the base (it embeds every stage)
  moved = false;
  return latticesBuilt;
}

int SceneDeformer::ObjectPipeline::prepareSubset(const Scene& scene, std::span<const Eigen::Index> indices) {
  if (subset && subset->stages.stages == full.stages && std::ranges::equal(subset->indices, indices))
    return subset->stages.sync(scene);
  const Eigen::MatrixX3d& own = full.pipeline->inputPoints();
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(indices.size()), 3);
  for (std::size_t i = 0; i < indices.size(); ++i) {
    const Eigen::Index v = indices[i];
    if (v < 0 || v >= own.rows() || (i > 0 && v <= indices[i - 1]))
      throw std::invalid_argument("SceneDeformer: a requested subset must hold increasing point indices below " +
                                  std::to_string(own.rows()) + "; entry " + std::to_string(i) + " is " + std::to_string(v));
    points.row(static_cast<Eigen::Index>(i)) = own.row(v);
  }
  auto made = std::make_unique<Subset>();
  made->indices.assign(indices.begin(), indices.end());
  const int latticesBuilt = made->stages.build(scene, std::make_unique<ffd::Pipeline>(points), full.stages);
  subset = std::move(made);
  return latticesBuilt;
}

void SceneDeformer::ObjectPipeline::remember(const SceneObject& object) {
  meshData = object.mesh.points.data();
  meshRows = object.mesh.points.rows();
  meshRevision = object.meshRevision;
}

void SceneDeformer::ObjectPipeline::recordRun() {
  const std::vector<ffd::StageReport>& reports = full.pipeline->lastReport();
  const auto changedOutput = [](const ffd::StageReport& r) { return r.outputChanged; };
  // Points that waited (a subset's, a followed motion's) are new to whoever read the last revision.
  const bool waited = coverage != PointCoverage::Full;
  const bool motionWaited = coverage == PointCoverage::Motion;
  coverage = PointCoverage::Full;
  const bool changed = std::any_of(reports.begin(), reports.end(), changedOutput);
  if (!waited && !changed) return;
  ++revision;
  // Only the last stage changed, by deltas (or nothing changed since the steps that waited, which
  // were such steps: the motion is back where the last pass left the points): the output moved
  // linearly in its control points since the base. Anything else makes this output the new base.
  const bool lastByDelta = (reports.back().delta || (motionWaited && !changed)) &&
                           std::none_of(reports.begin(), reports.end() - 1, changedOutput);
  if (!lastByDelta || baseControl.size() == 0) {
    baseRevision = revision;
    baseControl = full.pipeline->lattice(reports.back().id).controlPoints();
    moved = false;
    if (lastByDelta) baseControl.resize(0, 3);  // moved from an unknown base: nothing to follow
  } else {
    moved = true;
  }
  recordMotion();
}

void SceneDeformer::ObjectPipeline::recordMotion() {
  movedControl = -1;
  if (!moved) return;
  const std::optional<GestureMotion> motion = motionSinceBase();
  if (!motion || motion->controlPoints.size() != 1) return;
  movedControl = motion->controlPoints.front();
  movedBy = motion->displacements.row(0).transpose();
}

bool SceneDeformer::ObjectPipeline::mayWait() const {
  if (!moved || movedControl < 0 || coverage == PointCoverage::Subset || !full.pipeline->onlyLastStageMovesByDeltas())
    return false;
  const std::optional<GestureMotion> motion = motionSinceBase();
  return motion && motion->controlPoints.size() == 1 && motion->controlPoints.front() == movedControl;
}

void SceneDeformer::ObjectPipeline::recordWaitingStep() {
  const Eigen::Vector3d before = movedBy;
  recordMotion();
  if (movedBy != before || coverage != PointCoverage::Motion) ++revision;
  coverage = PointCoverage::Motion;
}

void SceneDeformer::ObjectPipeline::recordSubsetRun() {
  const std::vector<ffd::StageReport>& reports = subset->stages.pipeline->lastReport();
  const bool changed = std::any_of(reports.begin(), reports.end(), [](const ffd::StageReport& r) { return r.outputChanged; });
  if (changed || coverage != PointCoverage::Subset) ++revision;
  coverage = PointCoverage::Subset;
  baseControl.resize(0, 3);  // the full points' motion is not followed across subset runs
  moved = false;
  movedControl = -1;
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

bool SceneDeformer::covers(const EvaluationRequest& request) const {
  for (const auto& [id, p] : objects_) {
    if (p->coverage == PointCoverage::Full) continue;
    if (!gesture_) return false;
    if (p->coverage == PointCoverage::Motion) {
      if (!request.followed.count(id) || request.subsets.count(id)) return false;
      continue;
    }
    const auto asked = request.subsets.find(id);
    if (asked == request.subsets.end() || !std::ranges::equal(asked->second, p->subset->indices)) return false;
  }
  return true;
}

bool SceneDeformer::evaluate(const Scene& scene, const EvaluationRequest& request) {
  // Nothing changed since the last run, which already gave what the gesture state and the
  // request ask for.
  if (&scene == evaluated_ && markOf(scene) == evaluatedMark_ && (gesture_ || exact_) && covers(request)) return false;
  if (gesture_) {
    run(scene, gestureLattice_, Run::Gesture, nullptr, request);
  } else {
    run(scene, std::nullopt, Run::Finish);  // exact, in full: a request's subsets wait for gestures
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
                        Scene* takeFrom, const EvaluationRequest& request) {
  const bool exact = how == Run::Finish;
  const auto start = std::chrono::steady_clock::now();
  // 1. Sync every object's pipeline with the scene, in place (nothing is embedded yet), so that a
  //    throw in step 2 leaves each pipeline whole. An object the request names during a gesture
  //    syncs and runs its subset pipeline instead, when its full one needs no rebuild.
  struct Job {
    ObjectPipeline* object;
    detail::StagePipeline* stages;  // object->full or object->subset->stages
  };
  std::vector<Job> jobs;
  std::vector<ObjectPipeline*> waiting;  // followed objects whose step waits (EvaluationRequest::followed)
  std::set<ObjectId> present;
  labels_.clear();
  int latticesBuilt = 0;
  for (const auto& object : scene.objects()) {
    present.insert(object.id);
    labels_.emplace(object.name, object.id);
    auto found = objects_.find(object.id);
    std::unique_ptr<ObjectPipeline> added;  // a new object enters objects_ once it is synced
    ObjectPipeline* p = found != objects_.end() ? found->second.get() : (added = std::make_unique<ObjectPipeline>()).get();
    std::vector<Stage> stages = detail::stagesFor(scene, object.id);
    const Eigen::MatrixX3d& own = object.mesh.points;
    const ffd::Pipeline* built = p->full.pipeline.get();
    // A mesh at another address (a copied scene, an undo of an object edit) may still be the same:
    // compare it then, once, rather than rebuild.
    const bool inputChanged = !p->holdsSameMesh(object) &&
                              (!built || built->inputPoints().rows() != own.rows() || built->inputPoints() != own);
    const bool rebuild = !built || inputChanged || stages != p->full.stages;
    const auto asked = how == Run::Gesture ? request.subsets.find(object.id) : request.subsets.end();
    if (asked != request.subsets.end() && !rebuild && !stages.empty()) {
      latticesBuilt += p->prepareSubset(scene, asked->second);
      p->subset->stages.prepareRun(scene, activeLattice, ffd::UpdateMode::Exact, precision_);  // no drift to undo at release
      jobs.push_back({p, &p->subset->stages});
    } else {
      latticesBuilt += rebuild ? p->rebuild(scene, object, std::move(stages), takeFrom) : p->full.sync(scene);
      if (!p->full.stages.empty()) {
        p->full.prepareRun(scene, activeLattice, how == Run::Gesture ? ffd::UpdateMode::Delta : ffd::UpdateMode::Exact,
                           precision_);
        if (how == Run::Gesture && !rebuild && request.followed.count(object.id) && p->mayWait())
          waiting.push_back(p);  // its caller follows the motion: the delta pass waits
        else
          jobs.push_back({p, &p->full});
      }
    }
    p->remember(object);
    if (added) objects_[object.id] = std::move(added);
  }
  std::erase_if(objects_, [&present](const auto& entry) { return !present.count(entry.first); });

  // 2. Run the pipelines; progress counts the points every one of them embeds.
  std::vector<Eigen::Index> toEmbed;
  Eigen::Index total = 0;
  if (progress_) {
    for (const Job& job : jobs) total += toEmbed.emplace_back(job.stages->pipeline->pointsToEmbed(exact));
  }
  const auto goOn = [this, total](Eigen::Index done) {
    return progress_(total > 0 ? double(std::min(done, total)) / double(total) : 0.0);
  };
  if (progress_ && !goOn(0)) throw ffd::Cancelled("scene deformer: cancelled before any embedding");
  SceneDeformStats stats;
  stats.latticesBuilt = latticesBuilt;
  for (ObjectPipeline* p : waiting) p->recordWaitingStep();  // nothing of it can throw
  stats.waitingObjects = static_cast<int>(waiting.size());
  Eigen::Index done = 0;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    ObjectPipeline& p = *jobs[i].object;
    detail::StagePipeline& stages = *jobs[i].stages;
    const bool atSubset = &stages != &p.full;
    ffd::EmbedProgress hook;
    if (progress_ && toEmbed[i] > 0) hook = [&goOn, done](Eigen::Index d, Eigen::Index) { return goOn(done + d); };
    // exact: re-embed every throttled stage too (one pipeline pass, not an update and then another).
    if (exact) {
      stages.pipeline->reembedAll(hook);
    } else {
      stages.pipeline->update(hook);
    }
    if (progress_) done += toEmbed[i];
    for (const auto& report : stages.pipeline->lastReport()) {
      stats.reembeddedStages += report.reembedded ? 1 : 0;
      stats.deltaStages += report.delta ? 1 : 0;
      stats.embedSeconds += report.embedSeconds;
    }
    if (atSubset) {
      stats.subsetPoints += stages.pipeline->inputPoints().rows();
      p.recordSubsetRun();
      continue;
    }
    // The object's points, and those of them its first stage left outside or failed to embed.
    stats.deformedPoints += stages.pipeline->inputPoints().rows();
    if (const ffd::Embedding* first = stages.pipeline->embedding(stages.ids.at(stages.stages.front().lattice))) {
      stats.outsidePoints += first->outsideCount();
      stats.failedPoints += first->failedCount();
    }
    p.recordRun();
  }
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats_ = stats;
  evaluated_ = takeFrom != nullptr ? nullptr : &scene;  // points taken over: evaluate anew
  evaluatedMark_ = markOf(scene);
  exact_ = how == Run::Finish;
  totals_.reembeddedStages += std::uint64_t(stats.reembeddedStages);
  totals_.latticesBuilt += std::uint64_t(stats.latticesBuilt);
  totals_.deformedPoints += std::uint64_t(stats.deformedPoints);
  totals_.subsetPoints += std::uint64_t(stats.subsetPoints);
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

std::string SceneDeformer::describe(ObjectId object) const {
  std::string text = toString(object);
  for (const auto& [name, id] : labels_)
    if (id == object) text = std::string("'").append(name).append("' (").append(text).append(")");
  return text;
}

const SceneDeformer::ObjectPipeline& SceneDeformer::fullyEvaluated(ObjectId object) const {
  const ObjectPipeline& p = pipelineOf(object);
  if (p.coverage == PointCoverage::Motion)
    throw PointsNotEvaluated("SceneDeformer: the last steps of the gesture moving object " + describe(object) +
                             " were recorded without deforming its points (its motion is followed: "
                             "EvaluationRequest::followed); evaluate the scene without naming it before reading its points");
  if (p.coverage == PointCoverage::Subset)
    throw PointsNotEvaluated("SceneDeformer: object " + describe(object) + " was evaluated at " +
                             std::to_string(p.subset->indices.size()) +
                             " of its points only (a subset requested during a gesture); evaluate the scene without a "
                             "subset for it before reading its full points");
  return p;
}

const SceneDeformer::ObjectPipeline& SceneDeformer::atSubset(ObjectId object) const {
  const ObjectPipeline& p = pipelineOf(object);
  if (p.coverage != PointCoverage::Subset)
    throw PointsNotEvaluated("SceneDeformer: object " + describe(object) + " was not evaluated at a subset; " +
                             (p.coverage == PointCoverage::Full ? "read points()" : "its motion is followed"));
  return p;
}

const Eigen::MatrixX3d& SceneDeformer::points(ObjectId object) const { return fullyEvaluated(object).full.pipeline->points(); }

PointCoverage SceneDeformer::coverage(ObjectId object) const { return pipelineOf(object).coverage; }

const Eigen::MatrixX3d& SceneDeformer::subsetPoints(ObjectId object) const {
  return atSubset(object).subset->stages.pipeline->points();
}

const std::vector<Eigen::Index>& SceneDeformer::subsetIndices(ObjectId object) const {
  return atSubset(object).subset->indices;
}

Eigen::MatrixX3d SceneDeformer::takePoints(ObjectId object) {
  (void)fullyEvaluated(object);  // throws for an unknown object or one evaluated at a subset
  evaluated_ = nullptr;  // the object is forgotten: the next evaluate() builds its pipeline again
  return objects_.extract(object).mapped()->full.pipeline->takePoints();
}

Eigen::Index SceneDeformer::pointCount(ObjectId object) const {
  return pipelineOf(object).full.pipeline->inputPoints().rows();
}

std::uint64_t SceneDeformer::revision(ObjectId object) const {
  return pipelineOf(object).revision;
}

std::optional<GestureMotion> SceneDeformer::gestureMotion(ObjectId object) const {
  auto it = objects_.find(object);
  if (it == objects_.end() || !it->second->moved) return std::nullopt;
  return it->second->motionSinceBase();
}

std::optional<GestureMotion> SceneDeformer::ObjectPipeline::motionSinceBase() const {
  if (baseControl.size() == 0 || full.stages.empty()) return std::nullopt;
  const ffd::LatticeId last = full.pipeline->order().back();
  const ffd::Lattice& lattice = full.pipeline->lattice(last);
  if (lattice.controlPoints().rows() != baseControl.rows()) return std::nullopt;
  if (lattice.isRational()) return std::nullopt;  // with weights the map is a ratio, not linear in the points
  GestureMotion motion;
  motion.baseRevision = baseRevision;
  for (const auto& [widget, id] : full.ids)
    if (id == last) motion.lattice = widget;
  std::vector<Eigen::Vector3d> moves;
  for (Eigen::Index f = 0; f < lattice.controlPoints().rows(); ++f) {
    if (lattice.controlPoints().row(f) == baseControl.row(f)) continue;
    motion.controlPoints.push_back(f);
    moves.push_back(lattice.frame().linear() * (lattice.controlPoints().row(f) - baseControl.row(f)).transpose());
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
  if (p.full.stages.empty()) throw std::invalid_argument("SceneDeformer: object " + toString(object) + " has no lattice");
  const ffd::LatticeId last = p.full.pipeline->order().back();
  const ffd::Embedding* embedding = p.full.pipeline->embedding(last);
  if (!embedding) throw std::invalid_argument("SceneDeformer: object " + toString(object) + " is not embedded yet");
  ffd::controlPointWeights(p.full.pipeline->lattice(last), *embedding, controlPoint, weights);
}

bool SceneDeformer::gestureWeights(ObjectId object, Eigen::Index controlPoint, Eigen::VectorXd& weights) const {
  const ObjectPipeline& p = pipelineOf(object);
  if (!p.full.stages.empty()) {
    const ffd::LatticeId last = p.full.pipeline->order().back();
    const ffd::Deformer* stage = p.full.pipeline->deformer(last);
    if (stage && stage->keptControlWeights(p.full.pipeline->lattice(last), controlPoint, weights)) return true;
  }
  controlWeights(object, controlPoint, weights);
  return false;
}

std::map<std::string, Eigen::MatrixX3d> deformScene(const Scene& scene) {
  SceneDeformer deformer;
  deformer.finishGesture(scene);  // the exact result in one pass
  std::map<std::string, Eigen::MatrixX3d> result;
  for (const auto& object : scene.objects()) result[object.name] = deformer.takePoints(object.id);
  return result;
}

}  // namespace ffdkit::scenes
