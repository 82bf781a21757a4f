// The parts library: every part is a closed-enough triangle mesh of unit size, and unknown
// names are refused (the renderer then draws the kind's default glyph).
#include <QTest>

#include <algorithm>
#include <filesystem>

#include "ffdkit/parts/parts.h"
#include "ffdkit/scenes/scene_file.h"
#include "ffdkit/scenes/widget_file.h"

class PartsTest : public QObject {
  Q_OBJECT

 private slots:
  void everyPartIsAValidMeshOfUnitSize() {
    const auto names = ffdkit::app::partNames();
    QCOMPARE(names.size(), std::size_t(4));
    for (const auto& name : names) {
      const auto mesh = ffdkit::app::partMesh(name);
      QVERIFY2(mesh.has_value(), name.c_str());
      QVERIFY(mesh->vertices.rows() > 100);
      QVERIFY(mesh->triangles.rows() > 100);
      QVERIFY(mesh->triangles.minCoeff() >= 0);
      QVERIFY(mesh->triangles.maxCoeff() < mesh->vertices.rows());
      const Eigen::Vector3d extent = mesh->vertices.colwise().maxCoeff() - mesh->vertices.colwise().minCoeff();
      QVERIFY2(extent.maxCoeff() > 0.5 && extent.maxCoeff() <= 1.2 + 1e-9, name.c_str());
    }
  }

  // A glyph names a default shape or a part; any other name is drawn as the kind's default
  // glyph (the press's handle once was "crank-handle": an arrow picked on an invisible ring).
  void everySampleGlyphIsADefaultShapeOrAPart() {
    namespace fs = std::filesystem;
    const auto parts = ffdkit::app::partNames();
    auto check = [&](const ffdkit::widgets::WidgetModel& model, const std::string& file) {
      for (auto affine : model.widgets(ffdkit::widgets::WidgetType::Affine)) {
        const std::string& shape = model.glyph(affine).shape;
        const bool known = shape.empty() || shape == "arrow" || shape == "ring" || shape == "cube" ||
                           std::find(parts.begin(), parts.end(), shape) != parts.end();
        QVERIFY2(known, qPrintable(QString::fromStdString(file + ": " + model.name(affine) + " has glyph '" + shape + "'")));
      }
    };
    int files = 0;
    for (const auto& entry : fs::directory_iterator(FFDKIT_SOURCE_DIR "/scenes/examples"))
      if (fs::is_directory(entry.path()))
        check(ffdkit::scenes::readScene(entry.path()).widgets, entry.path().string()), ++files;
    for (const auto& entry : fs::directory_iterator(FFDKIT_SOURCE_DIR "/widgets/examples"))
      check(ffdkit::scenes::readWidgetFile(entry.path()), entry.path().string()), ++files;
    QVERIFY(files > 20);
  }

  // The press's handle is the crank, placed so that its knob stands on the circle of radius one
  // glyph size where a rotate widget is picked: grabbing the knob grabs the handle.
  void thePressCrankReachesThePickCircle() {
    const auto scene = ffdkit::scenes::readScene(std::filesystem::path(FFDKIT_SOURCE_DIR "/scenes/examples/press"));
    const auto& glyph = scene.widgets.glyph(scene.widgets.find("handle"));
    QCOMPARE(glyph.shape, std::string("crank"));
    const auto mesh = ffdkit::app::partMesh(glyph.shape);
    QVERIFY(mesh.has_value());
    double reach = 0.0;
    for (Eigen::Index i = 0; i < mesh->vertices.rows(); ++i) {
      const Eigen::Vector3d p = glyph.partPlacement * Eigen::Vector3d(mesh->vertices.row(i).transpose());
      reach = std::max(reach, p.head<2>().norm());
    }
    QVERIFY2(reach > 1.0 && reach < 1.15, qPrintable(QString::number(reach)));
  }

  void unknownNamesAreNotParts() {
    QVERIFY(!ffdkit::app::partMesh("arrow").has_value());
    QVERIFY(!ffdkit::app::partMesh("").has_value());
  }
};

QTEST_APPLESS_MAIN(PartsTest)
#include "parts_test.moc"
