// The keyboard-shortcut table (app/gui/src/keyboard_shortcuts.h) is the one home of ffdkit's
// keys: every action of the window takes its keys from it and has no others, no two rows share
// keys in one context, docs/app.md lists exactly its rows, and Help > Keyboard Shortcuts (F1,
// pressed as a user does) shows them.
#include <QAction>
#include <QDialog>
#include <QTableWidget>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include "gui_test_support.h"
#include "keyboard_shortcuts.h"

using namespace ffdkit;
using namespace ffdkit::app::testing;
using app::MainWindow;

namespace {

// The rows of the table under the "## Keyboard shortcuts" heading of docs/app.md (not its header
// or separator lines).
std::vector<std::string> documentedRows() {
  std::ifstream in(FFDKIT_SOURCE_DIR "/docs/app.md");
  std::vector<std::string> rows;
  std::string line;
  bool inSection = false, header = true;
  while (std::getline(in, line)) {
    if (line.starts_with("## ")) {
      inSection = line == "## Keyboard shortcuts";
      continue;
    }
    if (!inSection) continue;
    if (!line.starts_with("|")) {
      if (!rows.empty()) break;  // the table ended
      continue;
    }
    if (header) {  // "| keys | where | does |" and "|---|---|---|"
      if (line.starts_with("|---")) header = false;
      continue;
    }
    rows.push_back(line);
  }
  return rows;
}

}  // namespace

class KeyboardShortcutsTest : public QObject {
  Q_OBJECT

 private slots:
  void init() {
    window_ = openWindow(QSize(1000, 700));
    QVERIFY(window_ != nullptr);
  }
  void cleanup() { window_.reset(); }

  // Each row naming an action gave that action its keys, and no action has keys the table lacks.
  void everyActionHasExactlyTheTablesKeys() {
    MainWindow& w = *window_;
    int withKeys = 0;
    for (QAction* a : w.findChildren<QAction*>()) {
      if (a->objectName().isEmpty()) {
        QVERIFY2(a->shortcuts().isEmpty(), qPrintable(a->text() + " has keys outside the table"));
        continue;
      }
      const QList<QKeySequence> expected = app::shortcutsOf(a->objectName().toStdString());
      QVERIFY2(a->shortcuts() == expected, qPrintable(a->objectName() + ": " + QKeySequence::listToString(a->shortcuts()) +
                                                      " instead of " + QKeySequence::listToString(expected)));
      if (!expected.isEmpty()) ++withKeys;
    }
    std::set<std::string> actions;
    for (const auto& s : app::keyboardShortcuts()) {
      QVERIFY2(!QKeySequence(QString(s.keys), QKeySequence::PortableText).isEmpty(), s.keys);
      QVERIFY2(std::string(s.description).size() > 3, s.keys);
      if (std::string_view(s.action).starts_with("action")) {
        QVERIFY2(w.findChild<QAction*>(s.action) != nullptr, s.action);
        actions.insert(s.action);
      }
    }
    QCOMPARE(withKeys, static_cast<int>(actions.size()));
  }

  // Within one context (menu actions of the window and of the view count as one, since Qt matches
  // both anywhere in the window) a key sequence means one thing.
  void noTwoRowsShareKeysInOneContext() {
    std::map<std::pair<int, QString>, std::string> seen;
    for (const auto& s : app::keyboardShortcuts()) {
      const int context = s.context == app::ShortcutContext::View ? static_cast<int>(app::ShortcutContext::Window)
                                                                   : static_cast<int>(s.context);
      const QString keys = QKeySequence(QString(s.keys), QKeySequence::PortableText).toString();
      const auto [it, fresh] = seen.emplace(std::make_pair(context, keys), s.action);
      QVERIFY2(fresh, qPrintable(keys + " is both " + QString::fromStdString(it->second) + " and " + s.action));
    }
  }

  // docs/app.md's shortcut table is the table, row for row (each row once; nothing else).
  void docsListEveryRow() {
    const std::vector<std::string> documented = documentedRows();
    QVERIFY2(!documented.empty(), "docs/app.md has no '## Keyboard shortcuts' table");
    std::multiset<std::string> expected;
    for (const auto& s : app::keyboardShortcuts()) expected.insert(app::shortcutMarkdownRow(s));
    for (const auto& row : expected)
      QVERIFY2(std::count(documented.begin(), documented.end(), row) == 1,
               qPrintable(QString::fromStdString("docs/app.md should list once: " + row)));
    for (const auto& row : documented)
      QVERIFY2(expected.count(row) == 1, qPrintable(QString::fromStdString("docs/app.md lists a row not in the table: " + row)));
  }

  // F1 opens Help > Keyboard Shortcuts, which lists the table.
  void helpShowsTheTable() {
    MainWindow& w = *window_;
    pressKey(w, Qt::Key_F1);
    auto* dialog = w.findChild<QDialog*>("keyboardShortcutsDialog");
    QVERIFY(dialog != nullptr);
    QVERIFY(QTest::qWaitForWindowExposed(dialog));
    auto* table = dialog->findChild<QTableWidget*>("shortcutsTable");
    QVERIFY(table != nullptr);
    const auto rows = app::keyboardShortcuts();
    QCOMPARE(table->rowCount(), static_cast<int>(rows.size()));
    for (int r = 0; r < table->rowCount(); ++r) {
      QCOMPARE(table->item(r, 0)->text(), app::shortcutKeysText(rows[static_cast<std::size_t>(r)]));
      QCOMPARE(table->item(r, 1)->text(), app::shortcutContextText(rows[static_cast<std::size_t>(r)].context));
      QCOMPARE(table->item(r, 2)->text(), QString(rows[static_cast<std::size_t>(r)].description));
    }
    dialog->close();
  }

 private:
  std::unique_ptr<MainWindow> window_;
};

int main(int argc, char** argv) { return runGuiTest<KeyboardShortcutsTest>(argc, argv); }

#include "keyboard_shortcuts_test.moc"
