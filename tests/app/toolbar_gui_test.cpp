// The operations toolbar as a designer meets it, under a real window and real events (Xvfb):
// every action has its own drawn icon, a tooltip names the action's keys, and the names can be
// shown under the icons (View > Toolbar Text Under Icons), remembered across sessions.
#include <QAction>
#include <QHelpEvent>
#include <QImage>
#include <QSettings>
#include <QToolBar>
#include <QToolButton>
#include <QToolTip>

#include <map>
#include <string>

#include "gui_test_support.h"
#include "toolbar_icons.h"

using namespace ffdkit;
using namespace ffdkit::app::testing;
using app::MainWindow;

namespace {
QToolBar* operationsToolbar(MainWindow& w) { return w.findChild<QToolBar*>("operationsToolbar"); }

/// The icon drawn at 24 x 24 pixels, as the toolbar draws it.
QImage drawn(const QIcon& icon) { return icon.pixmap(24, 24).toImage().convertToFormat(QImage::Format_ARGB32); }

/// Pixels with any opacity.
int paintedPixels(const QImage& image) {
  int count = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) count += qAlpha(image.pixel(x, y)) > 0 ? 1 : 0;
  return count;
}
}  // namespace

class ToolbarGuiTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = startWindow(QSize(1100, 760), StartSettings::Cleared);
    QVERIFY(window_ != nullptr);
  }
  void cleanup() { window_.reset(); }

  // Every action on the toolbar draws an icon of its own (not blank: the SVG engine is there and
  // the file was found), and every row of the icon table is on the toolbar.
  void everyToolbarActionHasItsOwnDrawnIcon() {
    MainWindow& w = *window_;
    QToolBar* toolbar = operationsToolbar(w);
    QVERIFY(toolbar != nullptr);
    std::map<std::string, QImage> images;
    for (QAction* a : toolbar->actions()) {
      if (a->isSeparator()) continue;
      const std::string name = a->objectName().toStdString();
      QVERIFY2(!a->icon().isNull(), name.c_str());
      const QImage image = drawn(a->icon());
      // Each icon covers a good part of its 576 pixels, and not all of them (a drawing).
      const int painted = paintedPixels(image);
      QVERIFY2(painted > 60 && painted < 576, qPrintable(QString("%1: %2 pixels").arg(a->objectName()).arg(painted)));
      for (const auto& [other, otherImage] : images)
        QVERIFY2(otherImage != image, qPrintable(QString("%1 looks like %2").arg(a->objectName(), other.c_str())));
      images[name] = image;
    }
    for (const app::ActionIcon& row : app::actionIcons()) QVERIFY2(images.count(row.action) == 1, row.action);
    QCOMPARE(images.size(), app::actionIcons().size());
  }

  // The pointer rests on a button: its tooltip says what it does and which key does it.
  void theTooltipNamesTheKeys() {
    MainWindow& w = *window_;
    w.openScene(kExamples / "default");
    QToolBar* toolbar = operationsToolbar(w);
    const std::pair<const char*, QString> expected[] = {
        {"actionDirectManipulation", "(D)"}, {"actionEditMode", "(Tab)"}, {"actionAddPrimitive", "Add Primitive"}};
    for (const auto& [name, text] : expected) {
      QWidget* button = toolbar->widgetForAction(action(w, name));
      QVERIFY(button != nullptr);
      // The pointer comes to rest on the button; Qt's hover timer then sends it the tooltip event
      // (sent here at once: a parallel test's window on the same display can take the pointer).
      QTest::mouseMove(button, button->rect().center());
      QHelpEvent rest(QEvent::ToolTip, button->rect().center(), button->mapToGlobal(button->rect().center()));
      QApplication::sendEvent(button, &rest);
      QVERIFY2(QToolTip::text().contains(text), qPrintable(QString("%1: '%2'").arg(name, QToolTip::text())));
      QToolTip::hideText();
    }
    QVERIFY(!action(w, "actionAddPrimitive")->toolTip().contains("("));  // no keys, none named
    // Undo names the step and its keys; both change with the document.
    dragArrow(w, w.scene().widgets.find("pull"), 0.2);
    const QString undoTip = action(w, "actionUndo")->toolTip();
    QVERIFY2(undoTip.startsWith("Undo ") && undoTip.contains("pull") && undoTip.endsWith("(Ctrl+Z)"), qPrintable(undoTip));
    QCOMPARE(action(w, "actionDirectManipulation")->toolTip().count("(D)"), 1);  // once, though set twice
  }

  // View > Toolbar Text Under Icons, clicked with the mouse: the buttons show their names under
  // their icons, and a new window (the next session) does too; clicked again, icons only.
  void textUnderIconsIsAnOptionThatIsRemembered() {
    MainWindow& w = *window_;
    QToolBar* toolbar = operationsToolbar(w);
    auto* undoButton = qobject_cast<QToolButton*>(toolbar->widgetForAction(action(w, "actionUndo")));
    QVERIFY(undoButton != nullptr);
    QCOMPARE(toolbar->toolButtonStyle(), Qt::ToolButtonIconOnly);
    const int iconOnlyHeight = undoButton->sizeHint().height();
    clickMenuItem(w, action(w, "actionToolbarTextUnderIcons"));
    QTRY_COMPARE(toolbar->toolButtonStyle(), Qt::ToolButtonTextUnderIcon);
    QCOMPARE(undoButton->toolButtonStyle(), Qt::ToolButtonTextUnderIcon);
    QVERIFY2(undoButton->sizeHint().height() > iconOnlyHeight + 5, "no room made for the text");
    QVERIFY(w.close());
    window_.reset();

    window_ = openWindow(QSize(1100, 760));
    QVERIFY(window_ != nullptr);
    QCOMPARE(operationsToolbar(*window_)->toolButtonStyle(), Qt::ToolButtonTextUnderIcon);
    QVERIFY(action(*window_, "actionToolbarTextUnderIcons")->isChecked());
    clickMenuItem(*window_, action(*window_, "actionToolbarTextUnderIcons"));
    QTRY_COMPARE(operationsToolbar(*window_)->toolButtonStyle(), Qt::ToolButtonIconOnly);
  }

 private:
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<ToolbarGuiTest>(argc, argv); }

#include "toolbar_gui_test.moc"
