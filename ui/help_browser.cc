#include "ui/help_browser.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QImage>
#include <QMenuBar>
#include <QMessageBox>
#include <QPushButton>
#include <QScrollBar>
#include <QTextBlock>
#include <QTextBrowser>
#include <QTextCursor>
#include <QTextDocument>
#include <QTextFragment>
#include <QVBoxLayout>
#include <functional>

namespace hexcal::ui {
namespace {

struct HelpPage {
  const char* title;
  const char* file;
};

constexpr HelpPage kPages[] = {
    {"&Operator's guide (the steps, panel by panel)", "gui.md"},
    {"&Acquisition: cameras, controllers, recording", "acquisition.md"},
    {"&Session folder and step states", "session.md"},
    {"&Calibration, uncertainty and verdicts", "calibration.md"},
    {"&Planning poses", "planner.md"},
    {"Camera and &target", "vision.md"},
    {"&Robot file", "robot-file.md"},
    {"Command &line (hexcal)", "cli.md"},
};

constexpr qint64 kMaxPageBytes = 4 << 20;

// Every image fragment of `document`, with the cursor that selects it.
void ForEachImage(QTextDocument* document, const std::function<void(QTextCursor&, QTextImageFormat)>& visit) {
  for (QTextBlock block = document->begin(); block.isValid(); block = block.next()) {
    for (QTextBlock::iterator it = block.begin(); !it.atEnd(); ++it) {
      const QTextFragment fragment = it.fragment();
      if (!fragment.isValid() || !fragment.charFormat().isImageFormat()) continue;
      QTextCursor cursor(document);
      cursor.setPosition(fragment.position());
      cursor.setPosition(fragment.position() + fragment.length(), QTextCursor::KeepAnchor);
      visit(cursor, fragment.charFormat().toImageFormat());
    }
  }
}

QImage ImageOf(QTextDocument* document, const QString& name) {
  const QVariant resource = document->resource(QTextDocument::ImageResource, QUrl(name));
  if (resource.canConvert<QImage>()) return resource.value<QImage>();
  if (resource.canConvert<QPixmap>()) return resource.value<QPixmap>().toImage();
  return {};
}

}  // namespace

QString DocsFolder() {
  const QStringList places = {qEnvironmentVariable("HEXCAL_DOCS_DIR"), QStringLiteral(HEXCAL_BUILD_DOCS_DIR),
                              "/usr/share/doc/hexcal"};
  for (const QString& place : places)
    if (!place.isEmpty() && QFileInfo(place + "/gui.md").isFile()) return place;
  return {};
}

HelpBrowser::HelpBrowser(QWidget* parent) : QDialog(parent), text_(new QTextBrowser), back_(new QPushButton("Back")) {
  setWindowTitle("hexcal help");
  text_->setObjectName("help_text");
  text_->setOpenLinks(false);
  connect(text_, &QTextBrowser::anchorClicked, this, [this](const QUrl& link) { FollowLink(link.toString()); });
  // Images load when the page does, relative to it: fit them to the width then.
  connect(text_, &QTextBrowser::sourceChanged, this, [this] { FitImages(); });
  back_->setObjectName("help_back");
  back_->setEnabled(false);
  back_->setToolTip("The page shown before (Alt+Left)");
  back_->setShortcut(QKeySequence::Back);
  connect(back_, &QPushButton::clicked, this, &HelpBrowser::Back);
  connect(text_, &QTextBrowser::backwardAvailable, back_, &QPushButton::setEnabled);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(back_);
  buttons->addStretch();
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(buttons);
  layout->addWidget(text_);
  resize(900, 640);
}

bool HelpBrowser::ShowPage(const QString& page) {
  const QString folder = DocsFolder();
  const QString path = QDir(folder).filePath(QFileInfo(page).fileName());
  if (folder.isEmpty() || !QFileInfo(path).isFile() || QFileInfo(path).size() > kMaxPageBytes) {
    text_->setPlainText("The documentation was not found (looked in $HEXCAL_DOCS_DIR, the source tree and "
                        "/usr/share/doc/hexcal). It is docs/" + page + " in hexcal's source.");
    return false;
  }
  // As a source (not setMarkdown): the images resolve relative to the page,
  // and the history holds it for Back.
  text_->setSource(QUrl::fromLocalFile(path), QTextDocument::MarkdownResource);
  setWindowTitle("hexcal help — " + QFileInfo(path).fileName());
  return true;
}

void HelpBrowser::FollowLink(const QString& link) {
  const QUrl url(link);
  // Links between the pages ("session.md#status") stay in the browser.
  if (url.isRelative() && url.path().endsWith(".md")) ShowPage(QFileInfo(url.path()).fileName());
}

bool HelpBrowser::CanGoBack() const { return text_->isBackwardAvailable(); }

void HelpBrowser::Back() {
  text_->backward();
  setWindowTitle("hexcal help — " + ShownPage());
}

QString HelpBrowser::ShownText() const { return text_->toPlainText(); }

QString HelpBrowser::ShownPage() const { return QFileInfo(text_->source().toLocalFile()).fileName(); }

QStringList HelpBrowser::Images() const {
  QStringList names;
  ForEachImage(text_->document(), [&](QTextCursor&, const QTextImageFormat& image) { names << image.name(); });
  return names;
}

QStringList HelpBrowser::MissingImages() const {
  QStringList missing;
  for (const QString& name : Images())
    if (ImageOf(text_->document(), name).isNull()) missing << name;
  return missing;
}

void HelpBrowser::FitImages() {
  const int width = text_->viewport()->width() - 2 * static_cast<int>(text_->document()->documentMargin()) -
                    text_->verticalScrollBar()->sizeHint().width();
  if (width <= 0) return;
  QTextDocument* document = text_->document();
  ForEachImage(document, [&](QTextCursor& cursor, QTextImageFormat image) {
    const QImage loaded = ImageOf(document, image.name());
    if (loaded.isNull() || loaded.width() <= 0) return;
    const int shown = std::min(loaded.width(), width);
    image.setWidth(shown);
    image.setHeight(static_cast<double>(loaded.height()) * shown / loaded.width());
    cursor.setCharFormat(image);
  });
}

void HelpBrowser::resizeEvent(QResizeEvent* event) {
  QDialog::resizeEvent(event);
  FitImages();
}

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
