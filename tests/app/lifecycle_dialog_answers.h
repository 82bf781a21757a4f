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

/// Types `path` into a file dialog's name field and presses Return, as a user does; returns what
/// went wrong, or an empty string once the dialog has closed. The dialog lists its folder in a
/// thread and updates its name field as the rows arrive, which can overwrite what was typed, and
/// a shown dialog whose name field has the focus ignores selectFile() (the dialog then opened
/// its own folder on accept and stayed open): so it types once the listing is there, and again
/// while the dialog stays open.
inline QString typeFilePath(QFileDialog* dialog, const std::filesystem::path& path) {
  auto* name = dialog->findChild<QLineEdit*>("fileNameEdit");
  auto* files = dialog->findChild<QFileSystemModel*>();
  if (name == nullptr || files == nullptr) return "a file dialog without a name field or a file system model";
  const QModelIndex folder = files->index(dialog->directory().absolutePath());
  (void)QTest::qWaitFor(  // a listing that takes longer only costs a retyping below
      [&] { return dialog->isVisible() && !files->canFetchMore(folder) && files->rowCount(folder) > 0; }, 10000);
  const QString typed = QString::fromStdString(path.string());
  for (int attempt = 0; attempt < 5 && dialog->isVisible(); ++attempt) {
    QTest::qWait(20 * (attempt + 1));
    name->setFocus();
    name->selectAll();
    QTest::keyClicks(name, typed);
    if (name->text() == typed) QTest::keyClick(name, Qt::Key_Return);
  }
  if (dialog->isVisible()) return "the file dialog did not take the typed path: its name field holds '" + name->text() + "'";
  return {};
}

/// Chooses `path` in an open-file dialog by typing it, as a user does.
inline ModalAnswers::Handler chooseFile(const std::filesystem::path& path) {
  return [path](QWidget* modal) {
    auto* dialog = qobject_cast<QFileDialog*>(modal);
    QVERIFY2(dialog != nullptr, qPrintable(modal->metaObject()->className()));
    const QString failure = typeFilePath(dialog, path);
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
