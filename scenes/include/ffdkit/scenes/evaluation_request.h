#pragma once

#include <map>
#include <set>
#include <span>
#include <stdexcept>

#include <Eigen/Core>

#include "ffdkit/scenes/object_id.h"

namespace ffdkit::scenes {

/// What the caller of SceneDeformer::evaluate() is going to read. The default, an empty request,
/// asks for every object's full points: what every exact reader passes (picking on the full mesh,
/// export, save, the CLI, Python). A view that draws a level-of-detail proxy of a large object
/// while a gesture runs asks for that object at the proxy's points only, so that a drag step
/// costs the proxy's size rather than the mesh's; the full mesh is evaluated once, exactly, when
/// the gesture ends or when a request that does not name the object comes. A view that follows a
/// drag of one control point with its own copy of an object's points and normals names the object
/// as followed, so that the deformer's delta passes over its full points wait the same way.
struct EvaluationRequest {
  /// Objects read only at some of their points while a gesture runs (between
  /// SceneDeformer::beginGesture and endGesture), each with those points' indices: increasing,
  /// each below the object's point count (the object's own point order). The spans must stay
  /// valid during the evaluate() call only. Outside a gesture the subsets are ignored (every
  /// object is evaluated in full and exactly); an object whose pipeline is new or changed
  /// (another mesh, another lattice tree) is evaluated in full whatever the request says.
  std::map<ObjectId, std::span<const Eigen::Index>> subsets;
  /// Objects whose full points the caller does not read while a gesture moves them by one control
  /// point of their last lattice stage: it follows that motion itself (SceneDeformer::gestureMotion
  /// and gestureWeights; the view's normals and points, app/render/src/gesture_normals.h). During a
  /// gesture, a step of such an object that moves the same one control point as its last
  /// evaluated step did, and nothing else of it, is recorded without deforming its points (their
  /// delta pass waits: PointCoverage::Motion); the first step of a motion, any other change and
  /// every request that does not name the object evaluate its points (all the steps that waited
  /// in one delta pass), and the gesture's end evaluates them exactly. An object also in `subsets`
  /// is evaluated at its subset.
  std::set<ObjectId> followed = {};
};

/// What an object's evaluated points cover after the last SceneDeformer evaluation.
enum class PointCoverage {
  Full,    ///< every point: SceneDeformer::points() reads them
  Subset,  ///< only the points of a request's subset: SceneDeformer::subsetPoints() reads them
  /// only the motion of the points since their last evaluation, one control point's
  /// (EvaluationRequest::followed): SceneDeformer::gestureMotion() reads it, the points wait
  Motion
};

/// Thrown by SceneDeformer::points() (and takePoints()) for an object whose last evaluation
/// covered only a requested subset of its points (PointCoverage::Subset) or only their motion
/// (PointCoverage::Motion): its full points are not up to date, so handing them out would be
/// handing out stale data. Evaluate with a request that does not name the object
/// (SceneDeformer::evaluate(scene)) before reading them.
class PointsNotEvaluated : public std::logic_error {
 public:
  /// The error with `what`: the object and what to evaluate.
  using std::logic_error::logic_error;
};

}  // namespace ffdkit::scenes
