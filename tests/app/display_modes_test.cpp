// Display modes rendered off screen (Xvfb): zebra stripes, curvature combs (the comb's math is
// in curvature_comb_test.cpp), curves as tubes or lines, and the scene-file keys of all.
#include <QGuiApplication>
#include <QImage>
#include <QTemporaryDir>
#include <QTest>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

#include "ffdkit/render/offscreen_render.h"
#include "ffdkit/render/scene_view.h"
#include "ffdkit/scenes/scene_deformer.h"
#include "ffdkit/scenes/scene_file.h"
#include "test_curves.h"

using namespace ffdkit;

namespace {

using app::testing::circle;

// A scene with a single sphere (no widgets) seen from the default camera.
// Changes the look of the scene's first object through the scene's edit (which stamps it).
template <class Change>
void editLook(scenes::Scene& scene, Change change) {
  scenes::DisplaySettings look = scene.objects()[0].display;
  change(look);
  scene.setObjectDisplay(scene.objects()[0].name, look);
}

scenes::Scene sphereScene(scenes::SurfaceStyle style) {
  scenes::Scene scene;
  scenes::SceneObject sphere;
  sphere.name = "sphere";
  scenes::PrimitiveOptions options;
  options.resolution = 64;
  sphere.source = options;
  sphere.mesh = scenes::buildObjectMesh(sphere.source, ".");
  sphere.display.surfaceStyle = style;
  scene.addObject(sphere);
  return scene;
}

QImage render(const scenes::Scene& scene, int width = 400, int height = 400) {
  QTemporaryDir dir;
  const std::filesystem::path png = dir.filePath("shot.png").toStdString();
  app::renderSceneToPng(scene, png, {.width = width, .height = height});
  QImage image(QString::fromStdString(png.string()));
  return image.convertToFormat(QImage::Format_RGB32);
}

double distance(const QColor& c, const Eigen::Vector3d& rgb) {
  return (Eigen::Vector3d(c.redF(), c.greenF(), c.blueF()) - rgb).norm();
}

struct LineStats {
  int objectPixels = 0;
  int stripePixels = 0;  ///< within 0.1 of a zebra colour
  int transitions = 0;   ///< bright <-> dark changes between successive object pixels
};

// Walks the image column x from top to bottom over the pixels that are not background.
LineStats scanColumn(const QImage& image, int x, const Eigen::Vector3d& background) {
  LineStats stats;
  int last = -1;
  for (int y = 0; y < image.height(); ++y) {
    const QColor c = image.pixelColor(x, y);
    if (distance(c, background) < 0.05) continue;
    ++stats.objectPixels;
    if (distance(c, app::kZebraDark) < 0.1 || distance(c, app::kZebraLight) < 0.1) ++stats.stripePixels;
    const int bright = c.lightness() > 128 ? 1 : 0;
    if (last >= 0 && bright != last) ++stats.transitions;
    last = bright;
  }
  return stats;
}

// A closed curve: a circle of radius 0.8 tilted toward a camera on the -y axis.
scenes::Scene circleCurveScene(double cameraDistance = 4.0) {
  scenes::Scene scene;
  scenes::SceneObject curve;
  curve.name = "circle";
  curve.mesh.points = circle(0.8, 120);
  curve.mesh.points.col(2) = curve.mesh.points.col(1);  // tilted toward the default camera
  curve.mesh.segments.resize(120, 2);
  for (int i = 0; i < 120; ++i) curve.mesh.segments.row(i) << i, (i + 1) % 120;
  curve.display.color = {0.9, 0.75, 0.1};
  scene.addObject(curve);
  scenes::Camera camera = scene.camera();
  camera.position = {0.0, -cameraDistance, 0.0};
  camera.focalPoint = {0.0, 0.0, 0.0};
  scene.setCamera(camera);
  return scene;
}

// A view kept across frames, as the GUI keeps it: show() once, then refresh() per change.
class LiveView {
 public:
  explicit LiveView(int size) : size_(size), view_(renderer_) {
    window_->SetOffScreenRendering(true);
    window_->SetSize(size, size);
    window_->AddRenderer(renderer_);
  }
  QImage draw(const scenes::Scene& scene) {
    scenes::SceneDeformer deformer;
    deformer.update(scene);
    deformer.finishGesture(scene);
    if (first_) {
      // The frame right after show() differs from later ones in a few dozen edge pixels (its
      // clipping range is VTK's own, later frames use the view's bounds): compare later frames.
      view_.show(scene, deformer);
      window_->Render();
      first_ = false;
    }
    view_.refresh(scene, deformer);
    window_->Render();
    vtkNew<vtkUnsignedCharArray> pixels;
    window_->GetPixelData(0, 0, size_ - 1, size_ - 1, 0, pixels);  // bottom-up RGB
    QImage image(size_, size_, QImage::Format_RGB32);
    for (int y = 0; y < size_; ++y)
      for (int x = 0; x < size_; ++x) {
        const unsigned char* p = pixels->GetPointer(3 * ((size_ - 1 - y) * size_ + x));
        image.setPixel(x, y, qRgb(p[0], p[1], p[2]));
      }
    return image;
  }

 private:
  int size_;
  vtkNew<vtkRenderer> renderer_;
  vtkNew<vtkRenderWindow> window_;
  app::SceneView view_;
  bool first_ = true;
};

}  // namespace

class DisplayModesTest : public QObject {
  Q_OBJECT

 private slots:
  void zebraStripesAlternateAcrossASphereAndShadingDoesNot() {
    const scenes::Scene shaded = sphereScene(scenes::SurfaceStyle::Shaded);
    const scenes::Scene zebra = sphereScene(scenes::SurfaceStyle::Zebra);
    const QImage a = render(shaded), b = render(zebra);
    const LineStats s = scanColumn(a, a.width() / 2, shaded.background());
    const LineStats z = scanColumn(b, b.width() / 2, zebra.background());
    qInfo("shaded: %d object pixels, %d transitions; zebra: %d object pixels, %d stripe-coloured, %d transitions",
          s.objectPixels, s.transitions, z.objectPixels, z.stripePixels, z.transitions);
    QVERIFY(s.objectPixels > 100);
    QVERIFY(std::abs(z.objectPixels - s.objectPixels) < 6);  // the same sphere
    QVERIFY(s.transitions <= 2);
    QVERIFY(z.transitions >= 10);
    QVERIFY(z.stripePixels > 0.85 * z.objectPixels);  // unlit: the two stripe colours, edges aside
    QVERIFY(s.stripePixels < 0.1 * s.objectPixels);

    // More stripes, more transitions.
    scenes::Scene dense = zebra;
    editLook(dense, [&](scenes::DisplaySettings& d) { d.zebraStripes = 2 * zebra.objects()[0].display.zebraStripes; });
    const LineStats d = scanColumn(render(dense), 200, zebra.background());
    QVERIFY2(d.transitions > 1.6 * z.transitions, qPrintable(QString("%1 vs %2").arg(d.transitions).arg(z.transitions)));
  }

  void zebraUsesTheDeformedNormals() {
    // The default sample: a sphere under a lattice with an arrow. Stretched by the arrow, its
    // stripes must be those of a mesh whose own points are the deformed points.
    scenes::Scene deformedScene = scenes::readScene(std::filesystem::path(FFDKIT_SOURCE_DIR "/scenes/examples/default"));
    editLook(deformedScene, [&](scenes::DisplaySettings& d) { d.surfaceStyle = scenes::SurfaceStyle::Zebra; });
    const widgets::WidgetId arrow = deformedScene.widgets.widgets(widgets::WidgetType::Affine).front();
    const QImage rest = render(deformedScene, 320, 320);

    // Drawn as the GUI does a drag step: show at rest, then refresh with the deformed points.
    vtkNew<vtkRenderer> renderer;
    vtkNew<vtkRenderWindow> window;
    window->SetOffScreenRendering(true);
    window->SetSize(320, 320);
    window->AddRenderer(renderer);
    app::SceneView view(renderer);
    scenes::SceneDeformer deformer;
    deformer.update(deformedScene);
    deformer.finishGesture(deformedScene);
    view.show(deformedScene, deformer);
    window->Render();
    deformedScene.widgets.setVariation(arrow, 0.4);
    deformer.update(deformedScene);
    deformer.finishGesture(deformedScene);
    view.refresh(deformedScene, deformer);
    window->Render();
    vtkNew<vtkUnsignedCharArray> pixels;
    window->GetPixelData(0, 0, 319, 319, 0, pixels);  // bottom-up RGB

    // The same shape as a mesh of its own (not deformed), same widgets drawn.
    scenes::Scene baked = deformedScene;
    baked.setAttachments({});
    scenes::MeshData bakedMesh = baked.objects()[0].mesh;
    bakedMesh.points = deformer.points(baked.objects()[0].name);
    baked.setObjectMesh(baked.objects()[0].name, std::move(bakedMesh));
    const QImage expected = render(baked, 320, 320);

    int differing = 0, fromRest = 0;
    for (int y = 0; y < 320; ++y)
      for (int x = 0; x < 320; ++x) {
        const unsigned char* p = pixels->GetPointer(3 * ((319 - y) * 320 + x));
        const QColor e = expected.pixelColor(x, y);
        const QColor r = rest.pixelColor(x, y);
        if (std::abs(p[0] - e.red()) + std::abs(p[1] - e.green()) + std::abs(p[2] - e.blue()) > 60) ++differing;
        if (std::abs(p[0] - r.red()) + std::abs(p[1] - r.green()) + std::abs(p[2] - r.blue()) > 60) ++fromRest;
      }
    qInfo("pixels differing from the baked mesh: %d, from the rest state: %d", differing, fromRest);
    QVERIFY(fromRest > 2000);           // the drag changed the stripes
    QVERIFY(differing < fromRest / 50);  // and they are the deformed surface's
  }

  void curvatureCombIsDrawnForCurves() {
    scenes::Scene scene = circleCurveScene(5.0);
    auto combPixels = [](const QImage& image) {
      int n = 0;
      for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) n += distance(image.pixelColor(x, y), app::kCombColour) < 0.15;
      return n;
    };
    const int without = combPixels(render(scene, 300, 300));
    editLook(scene, [&](scenes::DisplaySettings& d) { d.curvatureComb = true; });
    const int with = combPixels(render(scene, 300, 300));
    editLook(scene, [&](scenes::DisplaySettings& d) { d.combScale = 0.4; });
    const int longer = combPixels(render(scene, 300, 300));
    qInfo("comb pixels: off %d, on %d, scale 0.4 %d", without, with, longer);
    QCOMPARE(without, 0);
    QVERIFY(with > 300);
    QVERIFY(longer > with + 300);  // longer teeth
  }

  void aCurveDrawnAsALineIsThinnerThanItsTubeAndInItsColour() {
    scenes::Scene scene = circleCurveScene();
    const Eigen::Vector3d colour = scene.objects()[0].display.color;
    struct Count {
      int drawn = 0;     ///< not background
      int coloured = 0;  ///< within 0.1 of the object's colour
      int blended = 0;   ///< within 0.05 of a mix of the background and the object's colour
    };
    auto count = [&](const QImage& image) {
      Count c;
      const Eigen::Vector3d along = colour - scene.background();
      for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
          const QColor p = image.pixelColor(x, y);
          if (distance(p, scene.background()) < 0.05) continue;
          ++c.drawn;
          c.coloured += distance(p, colour) < 0.1;
          // Edge pixels are antialiased: a mix of the two colours, never a shade of the colour.
          const Eigen::Vector3d rgb(p.redF(), p.greenF(), p.blueF());
          const double t = std::clamp((rgb - scene.background()).dot(along) / along.squaredNorm(), 0.0, 1.0);
          c.blended += (scene.background() + t * along - rgb).norm() < 0.05;
        }
      return c;
    };
    LiveView view(500);
    const QImage tubeImage = view.draw(scene);
    editLook(scene, [&](scenes::DisplaySettings& d) { d.curveStyle = scenes::CurveStyle::Line; });
    const QImage lineImage = view.draw(scene);  // refresh(): the changed look rebuilds the actor
    editLook(scene, [&](scenes::DisplaySettings& d) { d.curveStyle = scenes::CurveStyle::Tube; });
    const QImage tubeAgain = view.draw(scene);
    const Count tube = count(tubeImage), line = count(lineImage);
    qInfo("tube: %d pixels (%d in the object's colour, %d mixed with the background); line: %d pixels (%d, %d)",
          tube.drawn, tube.coloured, tube.blended, line.drawn, line.coloured, line.blended);
    // The circle is ~1170 pixels round: the 2-pixel line, antialiased, covers ~3300 pixels, the
    // ~8-pixel-wide tube about three times that.
    QVERIFY(line.drawn > 1000);
    QVERIFY2(line.drawn < tube.drawn / 2, qPrintable(QString("line %1 vs tube %2").arg(line.drawn).arg(tube.drawn)));
    // Unlit: the colour itself, mixed with the background at the antialiased edges.
    QVERIFY(line.coloured > 0.3 * line.drawn);
    QVERIFY(line.blended > 0.95 * line.drawn);
    QVERIFY(tube.coloured < 0.2 * tube.drawn);  // shaded: lit and dark sides
    // Every line pixel lies on the tube (the same curve).
    int offTube = 0;
    for (int y = 0; y < lineImage.height(); ++y)
      for (int x = 0; x < lineImage.width(); ++x)
        offTube += distance(lineImage.pixelColor(x, y), scene.background()) >= 0.05 &&
                   distance(tubeImage.pixelColor(x, y), scene.background()) < 0.05;
    QVERIFY2(offTube < line.drawn / 50, qPrintable(QString("%1 line pixels off the tube").arg(offTube)));
    QCOMPARE(tubeAgain, tubeImage);  // switching back restores the tube

    // A fresh render of a scene saved with lines agrees with the live view.
    editLook(scene, [&](scenes::DisplaySettings& d) { d.curveStyle = scenes::CurveStyle::Line; });
    const Count fresh = count(render(scene, 500, 500));
    QVERIFY2(std::abs(fresh.drawn - line.drawn) < line.drawn / 20, qPrintable(QString::number(fresh.drawn)));

    // The comb is drawn for a line as for a tube.
    auto combPixels = [](const QImage& image) {
      int n = 0;
      for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) n += distance(image.pixelColor(x, y), app::kCombColour) < 0.15;
      return n;
    };
    editLook(scene, [&](scenes::DisplaySettings& d) { d.curvatureComb = true; });
    const int combOnLine = combPixels(render(scene, 300, 300));
    editLook(scene, [&](scenes::DisplaySettings& d) { d.curveStyle = scenes::CurveStyle::Tube; });
    const int combOnTube = combPixels(render(scene, 300, 300));
    qInfo("comb pixels: on a line %d, on a tube %d", combOnLine, combOnTube);
    QVERIFY(combOnTube > 300);
    QVERIFY(combOnLine >= combOnTube);  // the thinner curve hides less of it
  }

  void displayKeysRoundTripAndDefaultsAreNotWritten() {
    scenes::Scene scene = sphereScene(scenes::SurfaceStyle::Shaded);
    const std::string plain = scenes::sceneFileText(scene);
    for (const char* key : {"surfaceStyle", "zebraStripes", "zebraDirection", "curvatureComb", "combScale", "curveStyle"})
      QVERIFY2(plain.find(key) == std::string::npos, key);
    scenes::DisplaySettings d = scene.objects()[0].display;
    d.surfaceStyle = scenes::SurfaceStyle::Zebra;
    d.zebraStripes = 7;
    d.zebraDirection = {1.0, 0.5, 0.0};
    d.curvatureComb = true;
    d.combScale = 0.125;
    d.curveStyle = scenes::CurveStyle::Line;
    scene.setObjectDisplay(scene.objects()[0].name, d);
    const std::string text = scenes::sceneFileText(scene);
    std::istringstream in(text);
    const scenes::Scene back = scenes::readScene(in);
    QVERIFY(back.objects()[0].display == d);
    QCOMPARE(scenes::sceneFileText(back), text);
  }

  void badDisplayValuesAreRefusedWithTheirPlace() {
    const std::string good = scenes::sceneFileText(sphereScene(scenes::SurfaceStyle::Shaded));
    const std::string anchor = "\"visible\": true";
    QVERIFY(good.find(anchor) != std::string::npos);
    auto refusal = [&](const std::string& extra) -> std::string {
      std::string text = good;
      text.replace(text.find(anchor), anchor.size(), anchor + ", " + extra);
      std::istringstream in(text);
      try {
        scenes::readScene(in);
      } catch (const scenes::SceneFileError& e) {
        return e.what();
      }
      return "";
    };
    const std::string zero = refusal("\"zebraStripes\": 0");
    QVERIFY2(zero.find("zebraStripes") != std::string::npos && zero.find("[1, 256]") != std::string::npos, zero.c_str());
    QVERIFY(refusal("\"zebraStripes\": 2.5").find("zebraStripes") != std::string::npos);
    const std::string style = refusal("\"surfaceStyle\": \"plaid\"");
    QVERIFY2(style.find("plaid") != std::string::npos && style.find("zebra") != std::string::npos, style.c_str());
    QVERIFY(refusal("\"zebraDirection\": [0, 0, 0]").find("zebraDirection") != std::string::npos);
    QVERIFY(refusal("\"combScale\": -1").find("combScale") != std::string::npos);
    QVERIFY(refusal("\"curvatureComb\": 1").find("curvatureComb") != std::string::npos);
    const std::string curve = refusal("\"curveStyle\": \"ribbon\"");
    QVERIFY2(curve.find("/display/curveStyle") != std::string::npos && curve.find("ribbon") != std::string::npos &&
                 curve.find("tube, line") != std::string::npos,
             curve.c_str());
    QVERIFY(refusal("\"zebraStripes\": 5").empty());  // the splice itself is fine
  }
};

QTEST_GUILESS_MAIN(DisplayModesTest)
#include "display_modes_test.moc"
