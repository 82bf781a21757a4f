#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/ffd/cancelled.h"
#include "ffdkit/ffd/deformer.h"
#include "ffdkit/scenes/evaluation_request.h"
#include "ffdkit/scenes/scene.h"
#include "ffdkit/scenes/scene_changes.h"

namespace ffdkit::scenes {

/// Timing and work of the last SceneDeformer::update(), for the status bar and the CLI.
struct SceneDeformStats {
  double seconds = 0.0;           ///< wall time of the update
  int reembeddedStages = 0;       ///< lattice stages that (re)computed their embedding
  /// Points of full meshes deformed (an object evaluated at a requested subset adds nothing here:
  /// its points count in `subsetPoints`).
  Eigen::Index deformedPoints = 0;
  /// Points deformed at requested subsets (EvaluationRequest::subsets, during a gesture) in place
  /// of their objects' full meshes.
  Eigen::Index subsetPoints = 0;
  Eigen::Index outsidePoints = 0; ///< object points outside their first lattice
  Eigen::Index failedPoints = 0;  ///< points whose Newton embedding failed (left unchanged)
  double embedSeconds = 0.0;      ///< part of `seconds` spent computing embeddings (the rest: syncing, deforming)
  /// Pipeline lattices built anew from the model (a new object, lattice tree or rest shape); a
  /// drag step writes control points into the existing ones and builds none.
  int latticesBuilt = 0;
  /// Lattice stages updated by deltas (updateGesture): their points are exact to rounding only
  /// until finishGesture() or update() evaluates them in full.
  int deltaStages = 0;
  /// Objects whose gesture step was recorded without deforming their points: their caller follows
  /// the motion (EvaluationRequest::followed; coverage() is PointCoverage::Motion).
  int waitingObjects = 0;
};

/// How an object's points moved during a gesture, when that motion is linear in a few control
/// points of the object's last lattice stage (SceneDeformer::gestureMotion): the points equal the
/// points at `baseRevision` plus sum_c weight_c(point) * displacements.row(c), with weight_c =
/// SceneDeformer::controlWeights(object, controlPoints[c]) (up to the rounding of the deltas).
struct GestureMotion {
  std::uint64_t baseRevision = 0;  ///< SceneDeformer::revision(object) of the points the motion starts from
  widgets::WidgetId lattice;       ///< the object's last lattice stage, the one whose control points moved
  std::vector<Eigen::Index> controlPoints;  ///< flat indices (ffd::Lattice::index) that moved since the base
  Eigen::MatrixX3d displacements;  ///< their WORLD displacements since the base (frame.linear() * dP), a row each
};

/// Progress of SceneDeformer::update() / finishGesture(): the fraction in [0, 1] of the points the
/// call embeds (over all its objects and lattice stages), non-decreasing, 0.0 first and 1.0 once
/// the call is complete (only these two when nothing needs embedding). Called on the thread that
/// runs the call, about every ffd::kEmbedProgressChunk embedded points. Return false to cancel.
using SceneProgress = std::function<bool(double fraction)>;

/// Evaluates a scene: for each object, its attached lattice trees in pre-order (Kuriyama
/// 1996, secs. 6.2.3, 6.3.2), on the FFD engine's pipeline. Precompute apart from per-frame work:
/// embeddings are built on the first update and again only when a lattice's rest shape or
/// frame moves; an edit of control points is an incremental update.
///
/// Keep one SceneDeformer per open scene and call evaluate() where the edits of an operation end
/// (the app: once per model change it reports, after the last edit; the CLI and scripts: when
/// they read points): it is the one place that evaluates. It reads what changed since its last
/// evaluation (SceneMark, scene_changes.h): nothing changed, nothing done; during a gesture
/// (beginGesture .. endGesture) a step by deltas, otherwise the exact result. The caller says
/// what it will read (EvaluationRequest): during a gesture an object the request names is
/// evaluated at the requested points only (a view's level-of-detail proxy) and its full points
/// wait, marked as such (coverage(), PointCoverage::Subset: points() throws PointsNotEvaluated
/// rather than hand out stale points), until the gesture ends or a request that does not name it
/// comes. An object the request says its caller follows (EvaluationRequest::followed: a view that
/// moves its own copy of the points and normals along gestureMotion()) keeps its delta passes
/// waiting while the gesture moves one control point of its last stage (PointCoverage::Motion:
/// points() throws likewise); the next evaluation that reads its points adds them in one pass,
/// and the gesture's end evaluates them exactly, as always. update(),
/// updateGesture() and finishGesture() are the steps evaluate() chooses from, public for tests
/// and the Python module's low-level deformer; application code calls evaluate() (a CTest check,
/// SingleEvaluationPoint, greps for other calls). It notices new objects and lattices, changed
/// attachments and sources. Change-driven: a lattice
/// whose revisions (WidgetModel::frameRevision, controlRevision) did not move since the last
/// update is not looked at; new control points are written in place into the stage's lattice and
/// deformed incrementally; a new frame moves the lattice and re-embeds it (per its throttle); no
/// lattice is rebuilt for a drag step. An object's own points are taken as unchanged while its
/// mesh keeps its address, size and SceneObject::meshRevision (Scene::setObjectMesh stamps it).
///
/// Pipelines are keyed by ObjectId: a renamed object keeps its pipeline and embeddings. The
/// accessors taking a name are for callers that speak names (tests, scripts): they mean the object
/// that had this name at the last update.
class SceneDeformer {
 public:
  SceneDeformer();
  ~SceneDeformer();
  /// Moves the deformer.
  SceneDeformer(SceneDeformer&&) noexcept;
  /// Moves the deformer.
  SceneDeformer& operator=(SceneDeformer&&) noexcept;

  // ---- evaluation: the one entry point --------------------------------------------------------
  /// A gesture starts (a drag, a live transform): until endGesture(), evaluate() takes the
  /// gesture's steps by deltas (updateGesture), re-embedding `activeLattice` at once.
  void beginGesture(std::optional<widgets::WidgetId> activeLattice = std::nullopt);
  /// The gesture ends (released or cancelled): the next evaluate() gives the exact result
  /// (finishGesture), also when nothing changed since the last step.
  void endGesture();
  /// True between beginGesture() and endGesture().
  bool inGesture() const { return gesture_; }
  /// Brings the deformed points up to date with `scene` when it changed since the last
  /// evaluation (its SceneMark moved, another scene, setPrecision, reset), a gesture's exact
  /// result is due, or `request` asks for points the last evaluation left out: once, by deltas
  /// during a gesture and exactly otherwise. The one place that decides what is evaluated: during
  /// a gesture, each object `request` names (EvaluationRequest::subsets) whose pipeline is built
  /// and unchanged in structure is evaluated at those points only (its own pipeline over them,
  /// built at the first such call and kept while the object's mesh, lattice tree and subset stay);
  /// each object it names as followed (EvaluationRequest::followed) whose step moves only the one
  /// control point of its last stage that its last evaluated step moved is not deformed: the step
  /// is recorded (revision(), gestureMotion(); coverage() is PointCoverage::Motion) and its delta
  /// pass waits for the next evaluation that reads the points;
  /// every other object, and every object outside a gesture, in full. Returns whether it
  /// evaluated. Throws as update(); after a throw the next call evaluates again.
  bool evaluate(const Scene& scene, const EvaluationRequest& request = {});
  /// evaluate() for a caller done with the objects' own points (the CLI): as
  /// finishGestureTakingPoints(), always exact.
  void evaluateTakingPoints(Scene& scene);

  /// Brings every object's deformed points up to date with `scene`.
  /// `activeLattice`: the lattice being dragged (always re-embedded at once; the others follow
  /// their re-embed policy). @throws ffd::LatticeError for a degenerate lattice.
  /// @throws ffd::Cancelled when the progress callback (setProgress) returns false. The deformer
  ///   stays usable: objects finished before the cancel hold their new points, the others their
  ///   previous ones (each object's points are always one complete evaluation), lastStats() is
  ///   unchanged, and the same call run again gives bit for bit the result of a call that was
  ///   never cancelled (only the embeddings not finished are computed again).
  void update(const Scene& scene, std::optional<widgets::WidgetId> activeLattice = std::nullopt);

  /// One step of a gesture (a drag, a live transform): as update(), except that a lattice whose
  /// embedding is fresh and whose control points moved is updated by deltas (ffd::UpdateMode::Delta:
  /// B_ijk(u,v,w) * dP_ijk per moved control point, one term per point instead of the (p+1)^3 of
  /// an exact evaluation). Its points then agree with update()'s to ~1e-16 relative per step (the
  /// rounding of the deltas accumulates slowly), not bit for bit: end the gesture with
  /// finishGesture(), which evaluates those lattices exactly again (as does update()).
  /// Progress and cancel as update().
  void updateGesture(const Scene& scene, std::optional<widgets::WidgetId> activeLattice = std::nullopt);

  /// Re-embeds every lattice that was throttled and evaluates in full every lattice updated by
  /// deltas (call on gesture release): the exact result, bit for bit that of update() calls
  /// without updateGesture(). Progress and cancel as update().
  void finishGesture(const Scene& scene);

  /// The arithmetic of the following calls' deformations (ffd::Precision; default Double). A
  /// change evaluates every lattice stage in full at the next call.
  void setPrecision(ffd::Precision precision) {
    if (precision != precision_) evaluated_ = nullptr;  // evaluate() runs again
    precision_ = precision;
  }
  /// The arithmetic of the following updates.
  ffd::Precision precision() const { return precision_; }

  /// finishGesture(scene) for a caller done with the objects' own points (the CLI): an object
  /// whose pipeline is built anew takes its points over from the scene (Scene::takeObjectPoints)
  /// instead of copying them, so the scene's meshes are left without points; read the results
  /// with takePoints(object). Progress and cancel as update(); on any other throw (non-finite
  /// points, a degenerate lattice) the points taken so far are lost with the call.
  void finishGestureTakingPoints(Scene& scene);

  /// Progress / cancel hook for the following update() and finishGesture() calls (empty: none).
  /// A worker thread typically passes a lambda that stores the fraction in an std::atomic the
  /// GUI polls and returns !cancelFlag.load().
  void setProgress(SceneProgress progress) { progress_ = std::move(progress); }

  /// Deformed points of an object (its own points if no lattice deforms it), #points x 3, as the
  /// last evaluation left them: a pure read (every evaluation that covers the object in full, a
  /// gesture's steps included, brings them up to date). @throws std::invalid_argument for an
  /// object update() has not seen; PointsNotEvaluated when the last evaluation covered only a
  /// requested subset of its points (coverage() is PointCoverage::Subset) or only their motion
  /// (PointCoverage::Motion).
  const Eigen::MatrixX3d& points(ObjectId object) const;
  /// points() of the object that had this name at the last update.
  const Eigen::MatrixX3d& points(const std::string& object) const;
  /// points(object), handed over without a copy, for a caller done with the deformation (the CLI
  /// writes them, deformScene returns them). The deformer forgets the object: the next run builds
  /// its pipeline again. @throws std::invalid_argument for an object update() has not seen;
  /// PointsNotEvaluated as points().
  Eigen::MatrixX3d takePoints(ObjectId object);
  /// takePoints() of the object that had this name at the last update.
  Eigen::MatrixX3d takePoints(const std::string& object);
  /// points(object).rows(). @throws std::invalid_argument for an object update() has not seen.
  Eigen::Index pointCount(ObjectId object) const;
  /// pointCount() of the object that had this name at the last update.
  Eigen::Index pointCount(const std::string& object) const;
  /// What the object's evaluated points cover: Full (points() reads them), after an evaluation
  /// at a requested subset during a gesture Subset (subsetPoints() reads them), or after a step
  /// recorded for a caller that follows the motion, Motion (gestureMotion() reads it).
  /// @throws std::invalid_argument for an object update() has not seen.
  PointCoverage coverage(ObjectId object) const;
  /// The object's deformed points at the subset the last evaluation was asked for,
  /// #subsetIndices() x 3 (row i: point subsetIndices()[i]), when coverage() is Subset.
  /// @throws std::invalid_argument for an object update() has not seen; PointsNotEvaluated when
  ///   coverage() is Full (read points() then: they are up to date).
  const Eigen::MatrixX3d& subsetPoints(ObjectId object) const;
  /// The point indices subsetPoints() holds (increasing). @throws as subsetPoints().
  const std::vector<Eigen::Index>& subsetIndices(ObjectId object) const;
  /// Grows whenever the object's evaluated points change (points(), subsetPoints() while the
  /// coverage is Subset, the motion while it is Motion): a view updates the object's arrays when
  /// it moved.
  /// @throws std::invalid_argument for an object update() has not seen.
  std::uint64_t revision(ObjectId object) const;
  /// revision() of the object that had this name at the last update.
  std::uint64_t revision(const std::string& object) const;

  /// Timing and work of the last update().
  const SceneDeformStats& lastStats() const { return stats_; }
  /// Lattice stages embedded (SceneDeformStats::reembeddedStages) and pipeline lattices built
  /// (latticesBuilt) over every call since the deformer was made: what an edit cost in
  /// precomputation, summed over the calls it caused (a rename must add nothing).
  struct Totals {
    std::uint64_t reembeddedStages = 0;  ///< sum of SceneDeformStats::reembeddedStages
    std::uint64_t latticesBuilt = 0;     ///< sum of SceneDeformStats::latticesBuilt
    /// Evaluations run (update(), updateGesture(), finishGesture(), and evaluate() when it
    /// evaluated): how a test sees that the events of one tick cost one evaluation.
    std::uint64_t evaluations = 0;
    /// Sum of SceneDeformStats::deformedPoints: the points of full meshes deformed.
    std::uint64_t deformedPoints = 0;
    /// Sum of SceneDeformStats::subsetPoints: the points deformed at requested subsets.
    std::uint64_t subsetPoints = 0;
  };
  /// The sums since the deformer was made (not reset by reset()).
  const Totals& totals() const { return totals_; }

  /// The motion of an object's points since their last evaluation that was not a delta step of
  /// its last lattice stage (updateGesture), when they moved since by such steps only: then the
  /// motion is linear in the control points that moved (ffd::controlPointWeights) and a consumer
  /// can follow it (the view's vertex normals: one cross product per vertex instead of a pass over
  /// the triangles). Also the steps recorded without deforming the points (PointCoverage::Motion)
  /// are such steps: the motion is the model's, however many of their delta passes wait.
  /// nullopt when the points are at their base (update(), finishGesture(), a re-embedding, a
  /// change of another stage) or the object is unknown.
  std::optional<GestureMotion> gestureMotion(ObjectId object) const;
  /// gestureMotion() of the object that had this name at the last update (nullopt for none).
  std::optional<GestureMotion> gestureMotion(const std::string& object) const;
  /// The weight of control point `controlPoint` of the object's last lattice stage for each of the
  /// object's points (ffd::controlPointWeights on that stage's embedding).
  /// @throws std::invalid_argument for an unknown object, one without lattices or not embedded yet;
  ///   ffd::LatticeError for a control point out of range.
  Eigen::VectorXd controlWeights(ObjectId object, Eigen::Index controlPoint) const;
  /// controlWeights() into `weights`, reusing its memory when it already has one entry per point
  /// (the view asks at the first step of every drag: no fresh buffer to fault in each time).
  /// @throws as controlWeights(), before `weights` is touched.
  void controlWeights(ObjectId object, Eigen::Index controlPoint, Eigen::VectorXd& weights) const;
  /// controlWeights() of the object that had this name at the last update.
  Eigen::VectorXd controlWeights(const std::string& object, Eigen::Index controlPoint) const;
  /// The weights a gesture's delta steps moved the object's points by when they moved
  /// `controlPoint` alone: what the last stage's deformer kept of them at such a step
  /// (ffd::Deformer::keptControlWeights, no second evaluation of the basis; they may differ from
  /// controlWeights() by the rounding of fused multiply-adds, ~1e-16 relative), else
  /// controlWeights(). `weights` is resized only when its size differs.
  /// @return true when the kept weights served.
  /// @throws as controlWeights(), before `weights` is touched.
  bool gestureWeights(ObjectId object, Eigen::Index controlPoint, Eigen::VectorXd& weights) const;

  /// Forgets every embedding (after an object's mesh was replaced).
  void reset();

 private:
  // How run() evaluates: update(), updateGesture(), finishGesture().
  enum class Run { Update, Gesture, Finish };
  // Syncs every object's pipeline with the scene, then runs it: incrementally (throttled stages
  // approximate; fresh ones by deltas for Gesture) or, for Finish, re-embedding every stale stage.
  // takeFrom: the same scene, when a pipeline built anew may take the object's points over.
  // subsets: for Gesture, the objects to evaluate at some points only (evaluate()'s request).
  void run(const Scene& scene, std::optional<widgets::WidgetId> activeLattice, Run how, Scene* takeFrom = nullptr,
           const EvaluationRequest& subsets = {});
  // True when the last run left every object's points as `request` asks (a Subset object named
  // by it with the same subset, during a gesture; every other object Full).
  bool covers(const EvaluationRequest& request) const;

  struct ObjectPipeline;
  // The object's pipeline. @throws std::invalid_argument for an object update() has not seen.
  ObjectPipeline& pipelineOf(ObjectId object) const;
  // The id of the object that had this name at the last run. @throws std::invalid_argument for none.
  ObjectId idOf(const std::string& object) const;
  // The object's pipeline when its full points are evaluated. @throws as points().
  const ObjectPipeline& fullyEvaluated(ObjectId object) const;
  // The object's pipeline when it was evaluated at a subset. @throws as subsetPoints().
  const ObjectPipeline& atSubset(ObjectId object) const;
  // "'name' (o3)", for messages.
  std::string describe(ObjectId object) const;
  std::map<ObjectId, std::unique_ptr<ObjectPipeline>> objects_;
  std::map<std::string, ObjectId, std::less<>> labels_;  // name -> id at the last run
  SceneDeformStats stats_;
  Totals totals_;
  SceneProgress progress_;
  ffd::Precision precision_ = ffd::Precision::Double;
  // evaluate(): the scene and its mark at the last run, whether that run was exact, the gesture.
  const Scene* evaluated_ = nullptr;
  SceneMark evaluatedMark_;
  bool exact_ = false;
  bool gesture_ = false;
  std::optional<widgets::WidgetId> gestureLattice_;
};

/// One-shot evaluation: the deformed points of every object, by name.
std::map<std::string, Eigen::MatrixX3d> deformScene(const Scene& scene);

}  // namespace ffdkit::scenes
