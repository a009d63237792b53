// Help > the documentation in docs/ (gui.md, acquisition.md, session.md,
// calibration.md, ...) shown in the application as rendered Markdown, with
// its screenshots and figures (docs/images/), each scaled down to the
// window's width, the links between the pages followed in place and Back to
// the page before. The folder is HEXCAL_DOCS_DIR if set, else the one the
// build was made from, else the installed one (/usr/share/doc/hexcal).
//
//   AddHelpMenu(menuBar(), this);  // Help > each page of docs/
//   HelpBrowser help(this);
//   help.ShowPage("gui.md");
#pragma once

#include <QDialog>
#include <QString>
#include <QStringList>

class QMenuBar;
class QPushButton;
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
  QString ShownPage() const;  // "gui.md"
  // The images the shown page names, and those of them that did not load.
  QStringList Images() const;
  QStringList MissingImages() const;
  // Follows a link as a click does ("session.md#status"); Back returns.
  void FollowLink(const QString& link);
  bool CanGoBack() const;
  void Back();

 protected:
  void resizeEvent(QResizeEvent* event) override;

 private:
  void FitImages();  // every image at most the page's width, its aspect kept

  QTextBrowser* text_;
  QPushButton* back_;
};

// The Help menu: one entry per page, and About.
void AddHelpMenu(QMenuBar* bar, QWidget* window);

}  // namespace hexcal::ui
