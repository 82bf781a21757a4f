#pragma once

// The monkey test's answers to the dialogs its actions open (monkey_gui_test.cpp).

#include <QAbstractButton>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QElapsedTimer>
#include <QFileDialog>
#include <QInputDialog>
#include <QLineEdit>
#include <QMessageBox>
#include <QPointer>
#include <QProgressDialog>
#include <QPushButton>
#include <QSpinBox>
#include <QTest>
#include <QTimer>

#include <filesystem>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "lifecycle_dialog_answers.h"

namespace ffdkit::app::testing {

/// Answers every modal dialog the actions open, from the running action's `answer` number:
/// message boxes by one of their buttons, file dialogs with a file of a fitting kind (or a broken
/// one, or Cancel), the rename dialog with a name, form dialogs with small values, then OK or
/// Cancel. A dialog still open after 10 s, or a file dialog that did not take its answer, is
/// closed and reported (`unanswered`).
class DialogAnswerer : public QObject {
 public:
  DialogAnswerer(std::filesystem::path files, std::vector<std::filesystem::path> widgetFiles, std::vector<std::filesystem::path> meshFiles)
      : files_(std::move(files)), widgetFiles_(std::move(widgetFiles)), meshFiles_(std::move(meshFiles)) {
    connect(&poll_, &QTimer::timeout, this, [this] { poll(); });
    poll_.start(10);
  }
  /// The next dialogs' answers come from `answer`.
  void setAnswer(std::uint32_t answer) { draw_.seed(answer); }
  const std::vector<std::string>& unanswered() const { return unanswered_; }
  std::string lastAnswers() {
    std::string text;
    std::swap(text, answers_);
    return text;
  }

 private:
  std::uint32_t next() { return static_cast<std::uint32_t>(draw_() >> 32); }

  void poll() {
    QWidget* modal = QApplication::activeModalWidget();
    if (modal == nullptr) return;
    if (modal->property("monkeyAnswered").toBool()) {
      if (modal != waiting_) {
        waiting_ = modal;
        since_.start();
      } else if (since_.elapsed() > 10000) {
        unanswered_.push_back(std::string(modal->metaObject()->className()) + " '" + modal->objectName().toStdString() +
                              "' '" + modal->windowTitle().toStdString() + "'");
        modal->close();
      }
      return;
    }
    modal->setProperty("monkeyAnswered", true);
    answer(modal);
  }

  void note(const std::string& what) { answers_ += (answers_.empty() ? "" : "; ") + what; }

  static void clickButton(QAbstractButton* button) {
    if (button != nullptr) QTest::mouseClick(button, Qt::LeftButton);
  }

  void answer(QWidget* modal) {
    if (auto* box = qobject_cast<QMessageBox*>(modal)) {
      const auto buttons = box->buttons();
      if (buttons.isEmpty()) return;
      QAbstractButton* button = buttons[static_cast<qsizetype>(next() % buttons.size())];
      note("message box '" + box->text().left(60).toStdString() + "': " + button->text().toStdString());
      clickButton(button);
      return;
    }
    if (auto* files = qobject_cast<QFileDialog*>(modal)) {
      answerFileDialog(files);
      return;
    }
    if (auto* progress = qobject_cast<QProgressDialog*>(modal)) {
      // Left to finish, or cancelled.
      if (next() % 3 == 0) {
        note("progress: Cancel");
        QTimer::singleShot(50, progress, [progress] { progress->cancel(); });
      }
      return;
    }
    if (auto* dialog = qobject_cast<QDialog*>(modal)) {
      answerForm(dialog);
      return;
    }
    note(std::string("closed ") + modal->metaObject()->className());
    modal->close();
  }

  void answerFileDialog(QFileDialog* dialog) {
    const bool cancel = next() % 4 == 0;
    if (cancel) {
      note("file dialog: Cancel");
      dialog->reject();
      return;
    }
    std::filesystem::path path;
    if (dialog->acceptMode() == QFileDialog::AcceptSave) {
      static constexpr const char* kSuffixes[] = {".obj", ".ply", ".stl", ".json", ".glb", ".vtp", ""};
      path = files_ / "out" / ("saved-" + std::to_string(++saved_) + kSuffixes[next() % std::size(kSuffixes)]);
    } else {
      const bool widgets = dialog->nameFilters().join(' ').contains("widget");
      const auto& candidates = widgets ? widgetFiles_ : meshFiles_;
      path = candidates[next() % candidates.size()];
    }
    note("file dialog: " + path.string());
    // Not a bare selectFile(): once the dialog's name field has the focus it ignores it, and the
    // dialog stayed open, at random, when the window system gave the focus before this answer.
    const QString failure = chooseFilePath(dialog, path);
    if (failure.isEmpty()) return;
    unanswered_.push_back("QFileDialog '" + dialog->windowTitle().toStdString() + "': " + failure.toStdString());
    dialog->reject();
  }

  void answerForm(QDialog* dialog) {
    std::string what = "dialog '" + dialog->objectName().toStdString() + "'";
    if (auto* input = qobject_cast<QInputDialog*>(dialog)) {
      static constexpr const char* kNames[] = {"", "renamed", "a b", "pull", "lattice1", "x/y", "   "};
      const QString name = QString::fromLatin1(kNames[next() % std::size(kNames)]);
      input->setTextValue(name);
      what += " text '" + name.toStdString() + "'";
    }
    // Small values keep a new lattice or primitive cheap: the minimum or a little above it.
    for (QSpinBox* spin : dialog->findChildren<QSpinBox*>()) spin->setValue(spin->minimum() + static_cast<int>(next() % 3));
    for (QComboBox* combo : dialog->findChildren<QComboBox*>())
      if (combo->count() > 0) combo->setCurrentIndex(static_cast<int>(next() % static_cast<std::uint32_t>(combo->count())));
    for (QCheckBox* check : dialog->findChildren<QCheckBox*>()) check->setChecked(next() % 2 == 0);
    if (auto* path = dialog->findChild<QLineEdit*>("path"))
      path->setText(QString::fromStdString((files_ / "out" / ("export-" + std::to_string(++saved_) + ".glb")).string()));
    const bool ok = next() % 4 != 0;
    note(what + (ok ? ": OK" : ": Cancel"));
    auto* buttons = dialog->findChild<QDialogButtonBox*>();
    QAbstractButton* button = nullptr;
    if (buttons != nullptr) button = buttons->button(ok ? QDialogButtonBox::Ok : QDialogButtonBox::Cancel);
    if (button != nullptr) clickButton(button);
    else if (ok) dialog->accept();
    else dialog->reject();
  }

  QTimer poll_;
  std::mt19937_64 draw_{0};
  std::filesystem::path files_;
  std::vector<std::filesystem::path> widgetFiles_, meshFiles_;
  int saved_ = 0;
  QPointer<QWidget> waiting_;
  QElapsedTimer since_;
  std::vector<std::string> unanswered_;
  std::string answers_;
};

}  // namespace ffdkit::app::testing
