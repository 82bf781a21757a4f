// The parts library: every part is a closed-enough triangle mesh of unit size, and unknown
// names are refused (the renderer then draws the kind's default glyph).
#include <QTest>

#include "ffdkit/app/parts.h"

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

  void unknownNamesAreNotParts() {
    QVERIFY(!ffdkit::app::partMesh("arrow").has_value());
    QVERIFY(!ffdkit::app::partMesh("").has_value());
  }
};

QTEST_APPLESS_MAIN(PartsTest)
#include "parts_test.moc"
