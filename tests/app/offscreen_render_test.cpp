// Off-screen rendering of a scene to PNG, as `ffdkit-cli render` does it.
#include <QGuiApplication>
#include <QImage>
#include <QTemporaryDir>
#include <QTest>

#include "ffdkit/render/offscreen_render.h"
#include "ffdkit/scenes/scene_file.h"

class OffscreenRenderTest : public QObject {
  Q_OBJECT

 private slots:
  void writesAPngShowingTheObject() {
    const auto scene = ffdkit::scenes::readScene(std::filesystem::path(FFDKIT_SOURCE_DIR "/scenes/examples/default"));
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const std::filesystem::path png = dir.filePath("default.png").toStdString();
    ffdkit::app::renderSceneToPng(scene, png, {.width = 320, .height = 240});

    QImage image(QString::fromStdString(png.string()));
    QVERIFY(!image.isNull());
    QCOMPARE(image.width(), 320);
    QCOMPARE(image.height(), 240);
    const QColor middle = image.pixelColor(160, 120);
    QVERIFY2(middle.red() > middle.blue() + 60, qPrintable(middle.name()));
    const QColor corner = image.pixelColor(2, 2);
    QVERIFY(std::abs(corner.red() - int(255 * scene.background().x() + 0.5)) <= 2);
    QVERIFY(std::abs(corner.blue() - int(255 * scene.background().z() + 0.5)) <= 2);
  }

  void rejectsAbsurdSizesWithoutWriting() {
    const auto scene = ffdkit::scenes::readScene(std::filesystem::path(FFDKIT_SOURCE_DIR "/scenes/examples/default"));
    QTemporaryDir dir;
    const std::filesystem::path png = dir.filePath("bad.png").toStdString();
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             ffdkit::app::renderSceneToPng(scene, png, {.width = 0, .height = 240}));
    QVERIFY(!std::filesystem::exists(png));
  }
};

QTEST_GUILESS_MAIN(OffscreenRenderTest)
#include "offscreen_render_test.moc"
