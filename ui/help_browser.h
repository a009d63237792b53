// Help > the documentation in docs/ (gui.md, session.md, calibration.md, ...)
// shown in the application as rendered Markdown, with the links between the
// pages followed in place. The folder is HEXCAL_DOCS_DIR if set, else the one
// the build was made from, else the installed one (/usr/share/doc/hexcal).
//
//   AddHelpMenu(menuBar(), this);  // Help > each page of docs/
//   HelpBrowser help(this);
//   help.ShowPage("gui.md");
#pragma once

#include <QDialog>
#include <QString>

class QMenuBar;
class QTextBrowser;

namespace hexcal::ui {

// The docs folder, or "" when none of the places has one.
QString DocsFolder();

class HelpBrowser : public QDialog {
  Q_OBJECT
 public:
  explicit HelpBrowser(QWidget* parent = nullptr);
  // Shows docs/`page` (e.g. "gui.md"); false when it cannot be read.
  bool ShowPage(const QString& page);
  QString ShownText() const;

 private:
  QTextBrowser* text_;
};

// The Help menu: one entry per page, and About.
void AddHelpMenu(QMenuBar* bar, QWidget* window);

}  // namespace hexcal::ui
