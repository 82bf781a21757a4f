#pragma once

// Answers to the modal dialogs of the document lifecycle (ModalAnswers handlers, real clicks):
// the message boxes' buttons and the file dialogs, shared by the lifecycle GUI tests.

#include <QFileDialog>
#include <QFileSystemModel>
#include <QLineEdit>
#include <QMessageBox>
#include <QPushButton>
#include <QSignalSpy>
#include <QTimer>

#include <filesystem>
#include <memory>

#include "gui_test_support.h"

namespace ffdkit::app::testing {

/// Clicks a message box's button with the mouse.
inline ModalAnswers::Handler clickButton(QMessageBox::StandardButton which) {
  return [which](QWidget* modal) {
    auto* box = qobject_cast<QMessageBox*>(modal);
    QVERIFY2(box != nullptr, qPrintable(modal->metaObject()->className()));
    QVERIFY2(box->button(which) != nullptr, qPrintable("no such button in: " + box->text()));
    QTest::mouseClick(box->button(which), Qt::LeftButton);
  };
}

/// Closes a test function's window (its cleanup() slot) as a user would, answering Discard when
/// it asks about unsaved changes, and destroys it.
inline void closeDiscardingChanges(std::unique_ptr<MainWindow>& window) {
  if (window && window->isModified()) {
    ModalAnswers discard({clickButton(QMessageBox::Discard)});
    window->close();
  }
  window.reset();
}

/// Reads a message box's title and text into `shown` ("title: text") and clicks OK.
inline ModalAnswers::Handler readMessage(QString* shown, QMessageBox::Icon icon) {
  return [=](QWidget* modal) {
    auto* box = qobject_cast<QMessageBox*>(modal);
    QVERIFY2(box != nullptr, qPrintable(modal->metaObject()->className()));
    *shown = box->windowTitle() + ": " + box->text();
    QCOMPARE(box->icon(), icon);
    QTest::mouseClick(box->button(QMessageBox::Ok), Qt::LeftButton);
  };
}

/// Chooses `path` in an open-file dialog and accepts it; returns what went wrong, or an empty
/// string once the dialog has closed. All in one go, with no events handled in between: the
/// dialog lists its folder in a thread and changes its selection and name field as rows arrive,
/// and a shown dialog whose name field has the focus ignores selectFile() (the dialog then
/// opened its own folder on accept and stayed open). So the name field gives up the focus,
/// selectFile() writes the name, selectedFiles() must be `path`, and then the dialog accepts.
inline QString chooseFilePath(QFileDialog* dialog, const std::filesystem::path& path) {
  auto* name = dialog->findChild<QLineEdit*>("fileNameEdit");
  if (name == nullptr) return "a file dialog without a name field";
  const QString wanted = QString::fromStdString(path.string());
  for (int attempt = 0; attempt < 3 && dialog->isVisible(); ++attempt) {
    if (attempt > 0) QTest::qWait(50);
    name->clearFocus();
    dialog->selectFile(wanted);
    if (dialog->selectedFiles() != QStringList{wanted}) continue;
    static_cast<QDialog*>(dialog)->accept();  // public through QDialog, virtual: QFileDialog::accept
  }
  if (dialog->isVisible())
    return "the file dialog did not take the path: it selects '" + dialog->selectedFiles().join("', '") +
           "', its name field holds '" + name->text() + "'";
  return {};
}

/// Chooses `path` in an open-file dialog (chooseFilePath).
inline ModalAnswers::Handler chooseFile(const std::filesystem::path& path) {
  return [path](QWidget* modal) {
    auto* dialog = qobject_cast<QFileDialog*>(modal);
    QVERIFY2(dialog != nullptr, qPrintable(modal->metaObject()->className()));
    const QString failure = chooseFilePath(dialog, path);
    QVERIFY2(failure.isEmpty(), qPrintable(failure));
  };
}

/// Answers a save dialog with `path`; `replacing` a file that exists, it also answers Yes when
/// the dialog asks whether to replace it. The dialog lists its folder asynchronously
/// (QFileSystemModel's gatherer thread) and updates its selection as the rows arrive, which can
/// overwrite a name chosen earlier (accept() then asked about another file, or changed folder and
/// stayed open, and the test hung at random under load): so it waits until `path`'s folder is
/// listed, then types the name. The question whether to replace is a modal inside accept(), which
/// runs in this handler, so ModalAnswers' timer cannot fire for it: a timer of the dialog answers.
inline ModalAnswers::Handler chooseSavePath(const std::filesystem::path& path, bool replacing = false) {
  return [path, replacing](QWidget* modal) {
    auto* dialog = qobject_cast<QFileDialog*>(modal);
    QVERIFY2(dialog != nullptr, qPrintable(modal->metaObject()->className()));
    auto* files = dialog->findChild<QFileSystemModel*>();
    auto* name = dialog->findChild<QLineEdit*>("fileNameEdit");
    QVERIFY(files != nullptr && name != nullptr);
    const QString folderPath = QString::fromStdString(path.parent_path().string());
    QSignalSpy listed(files, &QFileSystemModel::directoryLoaded);
    dialog->setDirectory(folderPath);
    const QModelIndex folder = files->index(folderPath);
    // Listed now, or already (then it shows rows: the folder holds the file being replaced).
    QTRY_VERIFY_WITH_TIMEOUT(listed.count() > 0 || (files->rowCount(folder) > 0 && !files->canFetchMore(folder)), 20000);
    name->selectAll();
    QTest::keyClicks(name, QString::fromStdString(path.filename().string()));
    QCOMPARE(dialog->selectedFiles(), QStringList{QString::fromStdString(path.string())});
    QTimer* replace = nullptr;
    if (replacing) {
      replace = new QTimer(dialog);
      QObject::connect(replace, &QTimer::timeout, dialog, [dialog, replace] {
        auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
        if (box == nullptr || box == static_cast<QWidget*>(dialog) || box->button(QMessageBox::Yes) == nullptr) return;
        replace->stop();
        QTest::mouseClick(box->button(QMessageBox::Yes), Qt::LeftButton);
      });
      replace->start(20);
    }
    static_cast<QDialog*>(dialog)->accept();  // public through QDialog, virtual: QFileDialog::accept
    if (replace != nullptr) QVERIFY2(!replace->isActive(), "the dialog did not ask whether to replace the file");
  };
}

}  // namespace ffdkit::app::testing
