#include "ffdkit/viewhost/vtk_view_widget.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QOpenGLFunctions>
#include <QWheelEvent>

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkGenericRenderWindowInteractor.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkNew.h>
#include <vtkOpenGLState.h>
#include <vtkRenderer.h>

namespace ffdkit::app {
namespace {


// VTK key symbols (X11 keysym names) for the keys interactor styles listen to.
const char* keySymbol(int key) {
  switch (key) {
    case Qt::Key_Left: return "Left";
    case Qt::Key_Right: return "Right";
    case Qt::Key_Up: return "Up";
    case Qt::Key_Down: return "Down";
    case Qt::Key_Return: return "Return";
    case Qt::Key_Enter: return "KP_Enter";
    case Qt::Key_Escape: return "Escape";
    case Qt::Key_Delete: return "Delete";
    case Qt::Key_Backspace: return "BackSpace";
    case Qt::Key_Tab: return "Tab";
    case Qt::Key_Space: return "space";
    case Qt::Key_Home: return "Home";
    case Qt::Key_End: return "End";
    case Qt::Key_PageUp: return "Prior";
    case Qt::Key_PageDown: return "Next";
    case Qt::Key_Shift: return "Shift_L";
    case Qt::Key_Control: return "Control_L";
    case Qt::Key_Alt: return "Alt_L";
    case Qt::Key_Plus: return "plus";
    case Qt::Key_Minus: return "minus";
    default: return nullptr;
  }
}

}  // namespace

struct VtkViewWidget::Impl {
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  vtkNew<vtkGenericRenderWindowInteractor> interactor;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  vtkNew<vtkCallbackCommand> makeCurrent;
  vtkNew<vtkCallbackCommand> isCurrent;
  vtkNew<vtkCallbackCommand> renderRequest;
  bool initialized = false;
  /// Whether something asked for a frame (requestRender) since VTK last rendered one.
  bool frameDue = true;
  /// The size (device pixels) of the frame VTK last rendered; empty before the first.
  QSize frameSize;
  std::uint64_t renders = 0;
  /// The camera's modification time when VTK last rendered a frame (vtkCamera::GetMTime).
  vtkMTimeType cameraDrawn = 0;
};

VtkViewWidget::VtkViewWidget(QWidget* parent) : QOpenGLWidget(parent), impl_(std::make_unique<Impl>()) {
  setFocusPolicy(Qt::StrongFocus);
  setMouseTracking(true);  // VTK styles hover-highlight on plain moves
  setUpdateBehavior(QOpenGLWidget::NoPartialUpdate);

  auto& d = *impl_;
  d.window->AddRenderer(d.renderer);
  d.window->SetMultiSamples(0);  // Qt owns the framebuffer format
  d.window->SetReadyForRendering(false);
  d.interactor->SetRenderWindow(d.window);
  d.interactor->SetInteractorStyle(d.style);
  // The interactor asks for renders while handling events; route them through Qt's paint cycle.
  d.interactor->EnableRenderOff();

  d.makeCurrent->SetClientData(this);
  // QOpenGLContext::makeCurrent, not QOpenGLWidget::makeCurrent: the widget's version also
  // binds its framebuffer, behind the back of VTK's GL state cache, and VTK calls MakeCurrent
  // in the middle of setting up its own framebuffers.
  d.makeCurrent->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
    QOpenGLContext* context = static_cast<VtkViewWidget*>(self)->context();
    if (context != nullptr && QOpenGLContext::currentContext() != context) context->makeCurrent(context->surface());
  });
  d.window->AddObserver(vtkCommand::WindowMakeCurrentEvent, d.makeCurrent);

  d.isCurrent->SetClientData(this);
  d.isCurrent->SetCallback([](vtkObject*, unsigned long, void* self, void* callData) {
    auto* widget = static_cast<VtkViewWidget*>(self);
    *static_cast<bool*>(callData) =
        widget->context() != nullptr && QOpenGLContext::currentContext() == widget->context();
  });
  d.window->AddObserver(vtkCommand::WindowIsCurrentEvent, d.isCurrent);

  d.renderRequest->SetClientData(this);
  d.renderRequest->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
    // The interactor style asks for a frame when it moved the camera, and again when its gesture
    // ends (a right or middle click with no motion too): only a camera moved since the last frame
    // draws something new.
    auto* widget = static_cast<VtkViewWidget*>(self);
    if (widget->impl_->renderer->GetActiveCamera()->GetMTime() != widget->impl_->cameraDrawn) widget->requestRender();
  });
  d.interactor->AddObserver(vtkCommand::RenderEvent, d.renderRequest);
}

VtkViewWidget::~VtkViewWidget() {
  // Release VTK's GPU resources while our context still exists.
  if (impl_->initialized && context() != nullptr) {
    makeCurrent();
    impl_->window->Finalize();
    doneCurrent();
  }
}

QSurfaceFormat VtkViewWidget::defaultFormat() {
  QSurfaceFormat format;
  format.setRenderableType(QSurfaceFormat::OpenGL);
  format.setVersion(3, 2);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setSwapBehavior(QSurfaceFormat::DoubleBuffer);
  format.setRedBufferSize(8);
  format.setGreenBufferSize(8);
  format.setBlueBufferSize(8);
  format.setAlphaBufferSize(8);
  format.setDepthBufferSize(24);
  format.setStencilBufferSize(8);
  format.setSamples(0);
  return format;
}

vtkGenericOpenGLRenderWindow* VtkViewWidget::renderWindow() const { return impl_->window; }
vtkRenderWindowInteractor* VtkViewWidget::interactor() const { return impl_->interactor; }
vtkRenderer* VtkViewWidget::renderer() const { return impl_->renderer; }

void VtkViewWidget::requestRender() {
  impl_->frameDue = true;
  update();
}

std::uint64_t VtkViewWidget::renders() const { return impl_->renders; }

void VtkViewWidget::initializeGL() {
  auto& d = *impl_;
  // Qt created the context and made it current: VTK must use it, not make its own.
  d.window->SetOwnContext(false);
  d.window->SetFrameBlitModeToBlitToCurrent();
  d.window->SetIsCurrent(true);
  d.window->OpenGLInitContext();
  d.interactor->Initialize();
  d.initialized = true;
  d.frameDue = true;  // a new context: nothing of VTK's last frame can be shown
}

void VtkViewWidget::resizeGL(int, int) {
  // Qt gives logical pixels; VTK works in device pixels.
  const double ratio = devicePixelRatioF();
  const int w = static_cast<int>(width() * ratio + 0.5);
  const int h = static_cast<int>(height() * ratio + 0.5);
  impl_->window->SetSize(w, h);
  impl_->interactor->UpdateSize(w, h);
  impl_->interactor->InvokeEvent(vtkCommand::ConfigureEvent, nullptr);
}

void VtkViewWidget::paintGL() {
  emit aboutToRender();
  auto& d = *impl_;
  // A screen change may have changed the device pixel ratio without a resize.
  const double ratio = devicePixelRatioF();
  const int w = static_cast<int>(width() * ratio + 0.5);
  const int h = static_cast<int>(height() * ratio + 0.5);
  if (d.window->GetSize()[0] != w || d.window->GetSize()[1] != h) resizeGL(width(), height());

  // Qt bound its own framebuffer and may have changed other GL state since the last frame:
  // VTK caches GL state, so let it read the real state before rendering, so that it blits
  // its image into the framebuffer Qt has bound (BlitToCurrent).
  vtkOpenGLState* state = d.window->GetState();
  state->ResetFramebufferBindings();
  state->ResetGLViewportState();
  state->ResetGLScissorState();
  state->ResetGLClearColorState();
  state->ResetGLDepthFuncState();
  state->ResetGLDepthMaskState();
  state->ResetGLColorMaskState();
  state->ResetGLBlendFuncState();
  state->ResetGLBlendEquationState();
  state->ResetGLCullFaceState();
  for (unsigned int capability : {GL_BLEND, GL_DEPTH_TEST, GL_SCISSOR_TEST, GL_CULL_FACE})
    state->ResetEnumState(capability);
  // A repaint that nothing asked for (the window was activated or deactivated, or Qt repaints
  // after the frame its resize event drew) at the size of the last frame shows that frame again:
  // VTK keeps it in its display framebuffer. Rendering it again would give the same pixels.
  if (d.frameDue || d.frameSize != QSize(w, h)) {
    d.frameDue = false;  // a request while VTK renders asks for the next frame
    d.frameSize = QSize(w, h);
    ++d.renders;
    d.window->SetReadyForRendering(true);
    d.window->Render();
    d.window->SetReadyForRendering(false);
    d.cameraDrawn = d.renderer->GetActiveCamera()->GetMTime();
  } else {
    d.window->BlitDisplayFramebuffer();
  }

  // VTK leaves alpha < 1 where the background shows; Qt would then blend the view with what
  // lies behind the window (Mesa), and screenshots come out transparent. Force alpha to 1.
  QOpenGLFunctions* gl = context()->functions();
  GLboolean colourMask[4];
  gl->glGetBooleanv(GL_COLOR_WRITEMASK, colourMask);
  GLfloat clearColour[4];
  gl->glGetFloatv(GL_COLOR_CLEAR_VALUE, clearColour);
  gl->glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
  gl->glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  gl->glClear(GL_COLOR_BUFFER_BIT);
  gl->glColorMask(colourMask[0], colourMask[1], colourMask[2], colourMask[3]);
  gl->glClearColor(clearColour[0], clearColour[1], clearColour[2], clearColour[3]);
}

namespace {

void setMouseInfo(vtkRenderWindowInteractor* interactor, const QWidget* widget, const QPointF& position,
                  Qt::KeyboardModifiers modifiers, int repeatCount) {
  const double ratio = widget->devicePixelRatioF();
  interactor->SetEventInformationFlipY(static_cast<int>(position.x() * ratio + 0.5),
                                       static_cast<int>(position.y() * ratio + 0.5),
                                       (modifiers & Qt::ControlModifier) ? 1 : 0,
                                       (modifiers & Qt::ShiftModifier) ? 1 : 0, 0, repeatCount);
  interactor->SetAltKey((modifiers & Qt::AltModifier) ? 1 : 0);
}

unsigned long pressEventFor(Qt::MouseButton button) {
  switch (button) {
    case Qt::LeftButton: return vtkCommand::LeftButtonPressEvent;
    case Qt::RightButton: return vtkCommand::RightButtonPressEvent;
    case Qt::MiddleButton: return vtkCommand::MiddleButtonPressEvent;
    default: return vtkCommand::NoEvent;
  }
}

unsigned long releaseEventFor(Qt::MouseButton button) {
  switch (button) {
    case Qt::LeftButton: return vtkCommand::LeftButtonReleaseEvent;
    case Qt::RightButton: return vtkCommand::RightButtonReleaseEvent;
    case Qt::MiddleButton: return vtkCommand::MiddleButtonReleaseEvent;
    default: return vtkCommand::NoEvent;
  }
}

}  // namespace

void VtkViewWidget::mousePressEvent(QMouseEvent* event) {
  setMouseInfo(impl_->interactor, this, event->position(), event->modifiers(), 0);
  if (auto id = pressEventFor(event->button()); id != vtkCommand::NoEvent) impl_->interactor->InvokeEvent(id);
  event->accept();
}

void VtkViewWidget::mouseDoubleClickEvent(QMouseEvent* event) {
  // VTK reports a double click as a press whose repeat count is 1.
  setMouseInfo(impl_->interactor, this, event->position(), event->modifiers(), 1);
  if (auto id = pressEventFor(event->button()); id != vtkCommand::NoEvent) impl_->interactor->InvokeEvent(id);
  event->accept();
}

void VtkViewWidget::mouseMoveEvent(QMouseEvent* event) {
  setMouseInfo(impl_->interactor, this, event->position(), event->modifiers(), 0);
  impl_->interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
  event->accept();
}

void VtkViewWidget::mouseReleaseEvent(QMouseEvent* event) {
  setMouseInfo(impl_->interactor, this, event->position(), event->modifiers(), 0);
  if (auto id = releaseEventFor(event->button()); id != vtkCommand::NoEvent) impl_->interactor->InvokeEvent(id);
  event->accept();
}

void VtkViewWidget::wheelEvent(QWheelEvent* event) {
  setMouseInfo(impl_->interactor, this, event->position(), event->modifiers(), 0);
  const QPoint delta = event->angleDelta();
  if (delta.y() > 0) impl_->interactor->InvokeEvent(vtkCommand::MouseWheelForwardEvent);
  if (delta.y() < 0) impl_->interactor->InvokeEvent(vtkCommand::MouseWheelBackwardEvent);
  if (delta.x() > 0) impl_->interactor->InvokeEvent(vtkCommand::MouseWheelLeftEvent);
  if (delta.x() < 0) impl_->interactor->InvokeEvent(vtkCommand::MouseWheelRightEvent);
  event->accept();
}

namespace {

void setKeyInfo(vtkRenderWindowInteractor* interactor, const QKeyEvent* event) {
  const QString text = event->text();
  const char keyCode = (text.size() == 1 && text[0].unicode() < 128) ? static_cast<char>(text[0].unicode()) : 0;
  const char* symbol = keySymbol(event->key());
  const QByteArray fallback = text.toLatin1();
  const Qt::KeyboardModifiers modifiers = event->modifiers();
  interactor->SetKeyEventInformation((modifiers & Qt::ControlModifier) ? 1 : 0,
                                     (modifiers & Qt::ShiftModifier) ? 1 : 0, keyCode,
                                     event->isAutoRepeat() ? 1 : 0,
                                     symbol != nullptr ? symbol : fallback.constData());
  interactor->SetAltKey((modifiers & Qt::AltModifier) ? 1 : 0);
}

}  // namespace

void VtkViewWidget::keyPressEvent(QKeyEvent* event) {
  setKeyInfo(impl_->interactor, event);
  impl_->interactor->InvokeEvent(vtkCommand::KeyPressEvent);
  // Interactor styles act on CharEvent ('r' resets the camera, 'w' wireframe, ...).
  impl_->interactor->InvokeEvent(vtkCommand::CharEvent);
  event->accept();
}

void VtkViewWidget::keyReleaseEvent(QKeyEvent* event) {
  setKeyInfo(impl_->interactor, event);
  impl_->interactor->InvokeEvent(vtkCommand::KeyReleaseEvent);
  event->accept();
}

void VtkViewWidget::enterEvent(QEnterEvent* event) {
  setMouseInfo(impl_->interactor, this, event->position(), event->modifiers(), 0);
  impl_->interactor->InvokeEvent(vtkCommand::EnterEvent);
  event->accept();
}

void VtkViewWidget::leaveEvent(QEvent* event) {
  impl_->interactor->InvokeEvent(vtkCommand::LeaveEvent);
  event->accept();
}

}  // namespace ffdkit::app
