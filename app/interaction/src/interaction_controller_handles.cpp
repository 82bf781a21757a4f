// The interaction controller, transformer handle drags: the manipulator of the selected affine
// widget or lattice (transformer.h), and a handle drag's motion applied to its target.
#include "ffdkit/interaction/interaction_controller.h"

#include <algorithm>

namespace ffdkit::app {

using widgets::WidgetId;
using widgets::WidgetType;

void InteractionController::beginHandleDrag(const Transformer& gizmo, TransformerHandle handle, const widgets::Ray& ray) {
  handleTarget_ = selection_.front();
  handleDrag_.emplace(gizmo, handle, ray);
  hoveredHandle_ = handle;
  recordDragStart();
  point_.reset();
  if (scene_.widgets.type(handleTarget_) == WidgetType::Affine) {
    // The placement is not part of WidgetModelState: the command stores it (release()).
    handleStart_ = true;
    placementStart_ = scene_.widgets.placement(handleTarget_);
    placementBase_ = scene_.widgets.placementBase(handleTarget_);
    dragLattice_.reset();
  } else {
    // A lattice moves through a gesture: its frame (a root) or its parent cell (a child)
    // follows, bound widgets too, and the attached objects are re-embedded as it moves.
    handleStart_ = false;
    dragStart_ = scene_.widgets.captureState();
    scene_.widgets.beginGesture(handleTarget_);
    dragLattice_ = handleTarget_;
  }
  dragging_ = true;
  deformer_.beginGesture(dragLattice_);
  notify();
}

void InteractionController::applyHandleMotion(const Eigen::Affine3d& motion) {
  if (handleStart_) {
    // F' = M * F with F = base * placement (WidgetModel::placementBase).
    scene_.widgets.setPlacement(handleTarget_, placementBase_.inverse() * motion * placementBase_ * placementStart_);
    notify();  // a placement moves no points
    return;
  }
  scene_.widgets.updateGesture(motion);
  notify();
}

std::optional<Transformer> InteractionController::transformer() const {
  if (selection_.size() != 1 || point_) return std::nullopt;
  const auto& m = scene_.widgets;
  const WidgetId id = selection_.front();
  if (!m.contains(id)) return std::nullopt;
  Transformer t;
  if (m.type(id) == WidgetType::Affine) {
    const widgets::WidgetFrame f = m.affineFrame(id);
    t.frame = f.frame;
    t.size = 2.5 * f.size;
    t.uniformSize = true;
    return t;
  }
  if (m.type(id) != WidgetType::Lattice) return std::nullopt;
  // At the centre of the rest lattice, along the rigid part of the frame (polar decomposition).
  const Eigen::Affine3d frame = m.latticeFrame(id);
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(frame.linear(), Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d rotation = svd.matrixU() * svd.matrixV().transpose();
  if (rotation.determinant() < 0.0) rotation = -rotation;  // a mirrored frame: keep right-handed axes
  const Eigen::MatrixX3d rest = m.worldRestPoints(id);
  t.frame.linear() = rotation;
  t.frame.translation() = rest.colwise().mean().transpose();
  t.size = std::max(0.3 * (rest.colwise().maxCoeff() - rest.colwise().minCoeff()).norm(), 1e-6);
  t.uniformSize = false;
  return t;
}

std::optional<TransformerHandle> InteractionController::transformerHandle() const {
  if (handleDrag_) return handleDrag_->handle();
  return transformer() ? hoveredHandle_ : std::nullopt;
}

}  // namespace ffdkit::app
