// ffdkit: the desktop application. main() only parses arguments and maps errors to exit codes.
#include <QApplication>
#include <QDockWidget>
#include <QToolBar>
#include <QCommandLineParser>
#include <QSurfaceFormat>
#include <QTimer>

#include <cstdio>
#include <exception>
#include <stdexcept>

#include "ffdkit/gui/main_window.h"
#include "ffdkit/viewhost/vtk_view_widget.h"
#include "timeline_widget.h"

namespace {

// --frame: the timeline's current frame (the model set to the animation there).
void goToFrame(ffdkit::app::MainWindow& window, const QString& text) {
  bool ok = false;
  const int frame = text.toInt(&ok);
  if (!ok) throw std::invalid_argument("--frame: expected a whole frame number, got '" + text.toStdString() + "'");
  window.findChild<ffdkit::app::TimelineWidget*>("timeline")->goTo(frame);
}

}  // namespace

int main(int argc, char** argv) {
  QSurfaceFormat::setDefaultFormat(ffdkit::app::VtkViewWidget::defaultFormat());
  QApplication app(argc, argv);
  QApplication::setApplicationName("ffdkit");

  QCommandLineParser parser;
  parser.setApplicationDescription("Direct-manipulation free-form deformation with 3D widgets.");
  parser.addHelpOption();
  parser.addPositionalArgument("scene", "Scene file or sample-scene folder to open.");
  QCommandLineOption screenshot("screenshot", "Render the scene, save the window's 3D view as PNG and exit.", "png");
  parser.addOption(screenshot);
  QCommandLineOption windowShot("window-screenshot", "Like --screenshot, but the whole window (outliner, properties).",
                                "png");
  parser.addOption(windowShot);
  QCommandLineOption select("select", "Select the widget of this name (shows its transformer and properties).", "widget");
  parser.addOption(select);
  QCommandLineOption frame("frame", "Go to this frame of the scene's animation (the timeline).", "frame");
  parser.addOption(frame);
  parser.process(app);

  try {
    ffdkit::app::MainWindow window;
    if (!parser.positionalArguments().isEmpty()) window.openScene(parser.positionalArguments().first().toStdString());
    if (parser.isSet(select)) window.selectWidget(parser.value(select).toStdString());
    if (parser.isSet(frame)) goToFrame(window, parser.value(frame));
    if (parser.isSet(screenshot) || parser.isSet(windowShot)) window.setLayoutRemembered(false);
    if (parser.isSet(screenshot)) {
      // Only the 3D view, at the size of the off-screen renderer.
      for (auto* dock : window.findChildren<QDockWidget*>()) dock->hide();
      for (auto* bar : window.findChildren<QToolBar*>()) bar->hide();
      window.resize(1024, 768);
    }
    window.show();
    if (parser.isSet(screenshot) || parser.isSet(windowShot)) {
      const bool whole = parser.isSet(windowShot);
      const QString png = parser.value(whole ? windowShot : screenshot);
      int status = 0;
      QTimer::singleShot(200, [&] {
        const QImage image = whole ? window.grab().toImage() : window.view()->grabFramebuffer();
        if (image.isNull() || !image.save(png, "PNG")) {
          std::fprintf(stderr, "ffdkit: cannot save screenshot to %s\n", qPrintable(png));
          status = 1;
        } else {
          std::printf("ffdkit: screenshot saved to %s\n", qPrintable(png));
        }
        QApplication::quit();
      });
      const int rc = QApplication::exec();
      return status != 0 ? status : rc;
    }
    // After a crash: offer the document the last session had not saved (autosave).
    QTimer::singleShot(0, &window, [&window] { window.offerRecovery(); });
    return QApplication::exec();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ffdkit: %s\n", e.what());
    return 1;
  }
}
