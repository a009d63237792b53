#include "ui/help_browser.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QMenuBar>
#include <QMessageBox>
#include <QTextBrowser>
#include <QVBoxLayout>

namespace hexcal::ui {
namespace {

struct HelpPage {
  const char* title;
  const char* file;
};

constexpr HelpPage kPages[] = {
    {"&Operator's guide (the steps, panel by panel)", "gui.md"},
    {"&Session folder and step states", "session.md"},
    {"&Calibration, uncertainty and verdicts", "calibration.md"},
    {"&Planning poses", "planner.md"},
    {"Camera and &target", "vision.md"},
    {"&Robot file", "robot-file.md"},
    {"Command &line (hexcal)", "cli.md"},
};

constexpr qint64 kMaxPageBytes = 4 << 20;

}  // namespace

QString DocsFolder() {
  const QStringList places = {qEnvironmentVariable("HEXCAL_DOCS_DIR"), QStringLiteral(HEXCAL_BUILD_DOCS_DIR),
                              "/usr/share/doc/hexcal"};
  for (const QString& place : places)
    if (!place.isEmpty() && QFileInfo(place + "/gui.md").isFile()) return place;
  return {};
}

HelpBrowser::HelpBrowser(QWidget* parent) : QDialog(parent), text_(new QTextBrowser) {
  setWindowTitle("hexcal help");
  text_->setObjectName("help_text");
  text_->setOpenLinks(false);
  connect(text_, &QTextBrowser::anchorClicked, this, [this](const QUrl& link) {
    // Links between the pages ("session.md#status") stay in the browser.
    if (link.isRelative() && link.path().endsWith(".md")) ShowPage(QFileInfo(link.path()).fileName());
  });
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(text_);
  resize(900, 640);
}

bool HelpBrowser::ShowPage(const QString& page) {
  const QString folder = DocsFolder();
  QFile file(QDir(folder).filePath(page));
  if (folder.isEmpty() || !file.open(QIODevice::ReadOnly) || file.size() > kMaxPageBytes) {
    text_->setPlainText("The documentation was not found (looked in $HEXCAL_DOCS_DIR, the source tree and "
                        "/usr/share/doc/hexcal). It is docs/" + page + " in hexcal's source.");
    return false;
  }
  text_->setMarkdown(QString::fromUtf8(file.readAll()));
  setWindowTitle("hexcal help — " + page);
  return true;
}

QString HelpBrowser::ShownText() const { return text_->toPlainText(); }

void AddHelpMenu(QMenuBar* bar, QWidget* window) {
  QMenu* help = bar->addMenu("&Help");
  for (const HelpPage& page : kPages) {
    const QString file = page.file;
    help->addAction(page.title, window, [window, file] {
      auto* browser = new HelpBrowser(window);
      browser->setAttribute(Qt::WA_DeleteOnClose);
      browser->ShowPage(file);
      browser->show();
    });
  }
  help->addSeparator();
  help->addAction("&About hexcal", window, [window] {
    QMessageBox::about(window, "About hexcal",
                       "hexcal: calibration of Gough–Stewart platforms with optimal measurement poses (IOOPS, "
                       "Daney, Papegay, Madeline, IJRR 2005). Docs: " +
                           (DocsFolder().isEmpty() ? QString("not found") : DocsFolder()));
  });
}

}  // namespace hexcal::ui
