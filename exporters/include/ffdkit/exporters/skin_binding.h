#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ffdkit/ffd/deformer.h"
#include "ffdkit/ffd/embedding.h"
#include "ffdkit/scenes/scene.h"

namespace ffdkit::exporters {

/// One joint of an FFD skin: a lattice control point (or the static joint, which never moves).
struct SkinJoint {
  std::string name;                    ///< "<lattice>[i,j,k]", or "rest" for the static joint
  widgets::WidgetId lattice{};         ///< unused for the static joint
  Eigen::Index controlPoint = -1;      ///< flat index (i + l (j + m k)); -1 for the static joint
  Eigen::Vector3d bindPosition = Eigen::Vector3d::Zero();  ///< world rest position at the bind state
};

/// The skin of one object: per vertex the joints of largest weight in the linear model
///   x(t) = Q + sum_stages sum_ijk s B_ijk(u,v,w) D_ijk(t),  D = F(t).linear() (P(t) - Pbar)
/// (each stage's (u,v,w) from embedding the object's own points Q in its bind-state rest
/// lattice; ffd/control_weights.h), written as a convex skin: joint weights w / c, the static
/// joint 1 - sum w / c, and joint translations c D (c = SkinBinding::jointScale).
struct ObjectSkin {
  std::string object;  ///< the object's name in the scene
  /// #vertices x kMax indices into SkinBinding::joints by decreasing weight (0: the static joint).
  Eigen::Matrix<std::int32_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> joints;
  /// #vertices x kMax weights of the full model (not renormalised; all of a vertex's weights,
  /// kept or not, sum to 1). Zero-weight slots hold joint 0.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> weights;
  /// The lattices deforming the object in pipeline order and deformers holding their
  /// bind-state embeddings of Q (for the linear model's own error, linearPositions, evaluated at
  /// every sample: kept here so that no sample copies an embedding; mutable because a deformer
  /// reuses its output buffer).
  std::vector<widgets::WidgetId> stages;
  mutable std::vector<ffd::Deformer> deformers;  ///< one per stage, holding its bind-state embedding
};

/// Joints and vertex weights of every lattice-deformed object of a scene.
struct SkinBinding {
  std::vector<SkinJoint> joints;  ///< joints[0] is the static joint "rest"
  /// c >= 1: the largest total weight sum_stages s over the vertices (1 unless stages overlap,
  /// e.g. a child lattice inside its parent); joint translations are scaled by it so that the
  /// weights stay convex.
  double jointScale = 1.0;
  int maxJoints = 0;  ///< kMax, the columns of ObjectSkin::joints
  std::vector<ObjectSkin> objects;  ///< one per lattice-deformed object
  /// Index of each lattice's first joint in `joints` (its control points follow in flat order).
  std::map<widgets::WidgetId, int> firstJoint;
};

/// Binds the skin at `bind`: the scene in its bind state (control points at rest; the caller
/// sets the time). Every object deformed by at least one lattice gets an ObjectSkin; every
/// lattice deforming an object contributes its control points as joints, in pipeline order.
/// @param maxJoints kMax, the weights kept per vertex (>= 1; 8 for glTF's two sets).
/// @throws ffd::LatticeError for a degenerate lattice.
SkinBinding bindSkin(const scenes::Scene& bind, int maxJoints);

/// World translation of every joint's node at the scene state `scene` (same widget tree as at
/// bind): bindPosition + c D_ijk; the static joint stays at the origin. #joints x 3.
Eigen::MatrixX3d jointTranslations(const SkinBinding& binding, const scenes::Scene& scene);

/// A vertex's first k joints of the full model, negative weights dropped, renormalised to sum 1
/// and rounded to float32 with the largest weight taking up the rounding (the float sum is 1 to
/// within one float ulp). Shapes #vertices x k.
struct PrunedSkin {
  int k = 0;  ///< joints kept per vertex
  Eigen::Matrix<std::uint16_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> joints;  ///< #vertices x k joint indices (glTF JOINTS_n)
  Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> weights;  ///< #vertices x k weights summing to 1 (glTF WEIGHTS_n)
};
PrunedSkin pruneSkin(const ObjectSkin& skin, int k);

/// Skinned positions as a glTF player computes them from float32 data (evaluated in double):
/// x = sum_slots w (Q + T_joint), T = translation(node) + translation(inverse bind matrix).
/// @param rest      #vertices x 3, the positions written (float32 values)
/// @param nodeTranslations, inverseBindTranslations  #joints x 3 (float32 values)
Eigen::MatrixX3d skinnedPositions(const Eigen::MatrixX3d& rest, const PrunedSkin& skin,
                                  const Eigen::MatrixX3d& nodeTranslations,
                                  const Eigen::MatrixX3d& inverseBindTranslations);

/// The unpruned linear model (all weights, double): Q + sum_stages (Deformer::deformStale of the
/// bind embedding with the stage's lattice at `scene`) - Q. Its distance to the exact FFD is
/// the error no k removes (child lattices re-embedded as their parent moves, moving frames).
Eigen::MatrixX3d linearPositions(const ObjectSkin& skin, const scenes::Scene& scene);

/// Rounds each value to float32 and back.
Eigen::MatrixX3d roundToFloat(const Eigen::MatrixX3d& values);

}  // namespace ffdkit::exporters
