// SceneView's transformer manipulator: its actors in an overlay renderer above the scene's.

#include "scene_view_impl.h"

#include <vtkArrowSource.h>
#include <vtkCubeSource.h>
#include <vtkNew.h>
#include <vtkParametricFunctionSource.h>
#include <vtkParametricTorus.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkTransform.h>

namespace ffdkit::app {

void SceneView::Impl::removeOverlay() {
  if (!overlay) return;
  if (vtkRenderWindow* window = overlay->GetRenderWindow()) window->RemoveRenderer(overlay);
  overlay = nullptr;
  overlayActors.clear();
  overlayHandles.clear();
  overlayPlaces.clear();
}

vtkRenderer* SceneView::Impl::overlayRenderer() {
  vtkRenderWindow* window = renderer->GetRenderWindow();
  if (window == nullptr) return nullptr;
  if (overlay && overlay->GetRenderWindow() == window) return overlay;
  removeOverlay();
  overlay = vtkSmartPointer<vtkRenderer>::New();
  overlay->SetLayer(renderer->GetLayer() + 1);
  overlay->SetInteractive(false);
  overlay->SetActiveCamera(renderer->GetActiveCamera());
  overlay->SetViewport(renderer->GetViewport());
  if (window->GetNumberOfLayers() < overlay->GetLayer() + 1) window->SetNumberOfLayers(overlay->GetLayer() + 1);
  window->AddRenderer(overlay);
  return overlay;
}

// The handles of TransformerLayout, red / green / blue per axis, the hovered or dragged one
// in the selection colour.
bool SceneView::Impl::sameShapes(const std::optional<Transformer>& a, const std::optional<Transformer>& b) {
  if (a.has_value() != b.has_value()) return false;
  return !a || (a->size == b->size && a->uniformSize == b->uniformSize);
}

// The overlay actors are built once per transformer's size; a transformer that moved (it
// follows a dragged widget every frame) moves them; the hovered or dragged handle recolours.
void SceneView::Impl::updateTransformer() {
  const bool placed = overlay && overlay->GetRenderWindow() == renderer->GetRenderWindow();
  if (!placed || !sameShapes(overlayBuiltFor, highlights.transformer)) {
    buildTransformer();
  } else if (highlights.transformer && overlayBuiltFor->frame.matrix() != highlights.transformer->frame.matrix()) {
    overlayBuiltFor = highlights.transformer;
    for (std::size_t k = 0; k < overlayActors.size(); ++k)
      placeOverlayActor(overlayActors[k], Eigen::Affine3d(highlights.transformer->frame) * overlayPlaces[k]);
  }
  const Eigen::Vector3d axisColour[3] = {{0.95, 0.25, 0.25}, {0.3, 0.9, 0.3}, {0.3, 0.5, 1.0}};
  for (std::size_t k = 0; k < overlayActors.size(); ++k) {
    const TransformerHandle handle = overlayHandles[k];
    const Eigen::Vector3d colour =
        highlights.transformerHandle == handle ? kSelected : axisColour[transformerAxis(handle)];
    overlayActors[k]->GetProperty()->SetColor(colour.x(), colour.y(), colour.z());
  }
}

void SceneView::Impl::placeOverlayActor(vtkActor* actor, const Eigen::Affine3d& place) {
  const Eigen::Matrix<double, 4, 4, Eigen::RowMajor> m = place.matrix();
  static_cast<vtkTransform*>(actor->GetUserTransform())->SetMatrix(m.data());
}

void SceneView::Impl::buildTransformer() {
  if (overlay) {
    for (auto& actor : overlayActors) overlay->RemoveActor(actor);
    overlayActors.clear();
  }
  overlayHandles.clear();
  overlayPlaces.clear();
  overlayBuiltFor = highlights.transformer;
  if (!highlights.transformer) return;
  ++stats.overlayBuilds;
  vtkRenderer* target = overlayRenderer();
  if (target == nullptr) return;
  using L = TransformerLayout;
  const Transformer& t = *highlights.transformer;
  const double s = t.size;
  auto add = [&](vtkPolyData* shape, const Eigen::Affine3d& place, TransformerHandle handle) {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(shape);
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    actor->GetProperty()->SetAmbient(0.35);  // colours: updateTransformer
    actor->SetUserTransform(vtkNew<vtkTransform>());
    placeOverlayActor(actor, Eigen::Affine3d(t.frame) * place);
    target->AddActor(actor);
    overlayActors.push_back(actor);
    overlayHandles.push_back(handle);
    overlayPlaces.push_back(place);
  };
  const double length = L::moveTip - L::moveFrom;
  if (!transformerArrow) {
    vtkNew<vtkArrowSource> arrow;  // along +x, length 1
    arrow->SetShaftRadius(0.025 / length);
    arrow->SetTipRadius(0.07 / length);
    arrow->SetTipLength((L::moveTip - L::moveTo) / length);
    arrow->SetShaftResolution(12);
    arrow->SetTipResolution(20);
    arrow->Update();
    transformerArrow = arrow->GetOutput();
    vtkNew<vtkParametricTorus> torus;  // about z
    torus->SetRingRadius(L::turnRadius);
    torus->SetCrossSectionRadius(0.018);
    vtkNew<vtkParametricFunctionSource> ring;
    ring->SetParametricFunction(torus);
    ring->SetUResolution(64);
    ring->SetVResolution(6);
    ring->Update();
    transformerRing = ring->GetOutput();
    vtkNew<vtkCubeSource> cube;
    cube->SetXLength(2.0 * L::sizeHalf);
    cube->SetYLength(2.0 * L::sizeHalf);
    cube->SetZLength(2.0 * L::sizeHalf);
    cube->Update();
    transformerCube = cube->GetOutput();
  }
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d a = Eigen::Vector3d::Unit(i);
    // Rotations taking +x (arrow) and +z (ring) onto axis i.
    const Eigen::Matrix3d xToAxis = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), a).toRotationMatrix();
    const Eigen::Matrix3d zToAxis = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), a).toRotationMatrix();
    add(transformerArrow,
        Eigen::Affine3d(Eigen::Scaling(s)) * Eigen::Affine3d(xToAxis) * Eigen::Translation3d(L::moveFrom, 0, 0) *
            Eigen::Scaling(length),
        static_cast<TransformerHandle>(i));
    add(transformerRing, Eigen::Affine3d(Eigen::Scaling(s)) * Eigen::Affine3d(zToAxis),
        static_cast<TransformerHandle>(3 + i));
    add(transformerCube, Eigen::Affine3d(Eigen::Scaling(s)) * Eigen::Translation3d(L::sizeAt * a),
        static_cast<TransformerHandle>(6 + i));
  }
}

}  // namespace ffdkit::app
