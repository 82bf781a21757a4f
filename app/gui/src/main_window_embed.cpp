// MainWindow::attachLattice: a large object is embedded in a worker thread behind a progress
// dialog that can cancel it.
#include <atomic>
#include <cmath>

#include <QEventLoop>
#include <QProgressDialog>
#include <QThread>
#include <QTimer>

#include "ffdkit/ffd/cancelled.h"
#include "main_window_impl.h"

namespace ffdkit::app {

using namespace window_detail;

namespace {
long backgroundPoints = 200000;
}

void MainWindow::setBackgroundEmbedPoints(long points) { backgroundPoints = points; }
long MainWindow::backgroundEmbedPoints() { return backgroundPoints; }

bool MainWindow::attachLattice(widgets::WidgetId lattice, const std::string& object) {
  Impl& d = *impl_;
  const scenes::SceneObject* target = d.scene.findObject(object);
  if (target == nullptr || target->mesh.points.rows() < backgroundPoints) {
    d.controller->attachLattice(lattice, object);
    return true;
  }
  // Embed on a copy of the scene in a worker thread; the GUI stays live, shows the embedding's
  // progress and can cancel it: the worker's progress hook reports into atomics that a timer
  // polls, and stops the embedding (ffd::Cancelled) at its next chunk once Cancel is pressed.
  struct Job {
    scenes::Scene scene;
    scenes::SceneDeformer deformer;
    std::string error;
    std::atomic<int> permille{0};
    std::atomic<bool> cancel{false};
  };
  auto job = std::make_shared<Job>();
  job->scene = d.scene;
  fitAndAttachLattice(job->scene, lattice, object);  // throws before anything starts
  job->deformer.setProgress([raw = job.get()](double fraction) {
    raw->permille.store(static_cast<int>(std::lround(1000.0 * fraction)));
    return !raw->cancel.load();
  });
  QThread* thread = QThread::create([job] {
    try {
      job->deformer.evaluate(job->scene);
    } catch (const ffd::Cancelled&) {
      // The copy is dropped below.
    } catch (const std::exception& e) {
      job->error = e.what();
    }
  });
  QProgressDialog progress(tr("Embedding %1 points of '%2'...").arg(target->mesh.points.rows()).arg(qs(object)),
                           tr("Cancel"), 0, 1000, this);
  progress.setObjectName("embedProgress");
  progress.setWindowModality(Qt::WindowModal);
  progress.setMinimumDuration(0);
  progress.setAutoReset(false);
  progress.setAutoClose(false);
  QTimer poll;
  connect(&poll, &QTimer::timeout, &progress, [&] { progress.setValue(job->permille.load()); });
  QEventLoop loop;
  connect(thread, &QThread::finished, &loop, &QEventLoop::quit);
  connect(&progress, &QProgressDialog::canceled, &loop, [&] {
    job->cancel.store(true);  // the worker stops at its next chunk; wait for it below
  });
  connect(thread, &QThread::finished, thread, &QObject::deleteLater);
  thread->start();
  progress.show();
  poll.start(30);
  loop.exec();  // until the worker has finished, cancelled or not
  poll.stop();
  progress.reset();
  const bool cancelled = job->cancel.load();
  job->deformer.setProgress({});  // the hook points into the job
  if (cancelled) return false;
  if (!job->error.empty()) throw std::runtime_error(job->error);
  d.controller->adoptDeformer(std::move(job->deformer));
  d.controller->attachLattice(lattice, object);  // the same edit: nothing left to embed
  return true;
}

}  // namespace ffdkit::app
