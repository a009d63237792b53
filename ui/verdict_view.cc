#include "ui/verdict_view.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QScrollArea>
#include <QScrollBar>
#include <algorithm>

#include "ui/gui_terms.h"
#include "ui/text_wrap.h"

namespace hexcal::ui {
namespace {

// A poor verdict's findings beyond these lines scroll, so that the table
// under the verdict keeps its rows at 1024×600 (issue 35).
constexpr int kFindingLines = 4;

QString Colour(workflow::VerdictLevel level) { return workflow::VerdictLevelColour(level); }

QString Html(const std::string& text) { return QString::fromStdString(text).toHtmlEscaped(); }

// Findings that need action in full, the good ones by name on one line.
QString FindingsHtml(const workflow::Verdict& verdict) {
  QString html, good;
  for (const workflow::Finding& f : verdict.findings) {
    if (f.level == workflow::VerdictLevel::kGood) {
      good += (good.isEmpty() ? "" : ", ") + Html(f.aspect);
      continue;
    }
    // What to do, on as few lines as possible; the figures are in the tooltip.
    html += QString("<span style=\"color:%1\"><b>%2</b></span> %3: %4.<br>")
                .arg(Colour(f.level), workflow::VerdictLevelName(f.level), Html(f.aspect),
                     InGuiTerms(Html(f.advice)));  // the GUI's controls, not the CLI's flags
  }
  if (!good.isEmpty()) {
    html += QString("<span style=\"color:%1\">%2:</span> %3")
                .arg(Colour(workflow::VerdictLevel::kGood), html.isEmpty() ? "every finding good" : "good", good);
  }
  return html;
}

QString FindingsTooltip(const workflow::Verdict& verdict) {
  QString tip;
  for (const workflow::Finding& f : verdict.findings) {
    tip += QString("<p><b>%1</b> (%2): %3 [%4]<br>%5</p>")
               .arg(Html(f.aspect), workflow::VerdictLevelName(f.level), Html(f.figure), Html(f.threshold),
                    Html(f.meaning));
  }
  return tip;
}

}  // namespace

VerdictView::VerdictView(QWidget* parent) : QWidget(parent) {
  setObjectName("verdict_view");
  level_ = new QLabel;
  level_->setObjectName("verdict_level");
  level_->setTextFormat(Qt::RichText);
  level_->setAlignment(Qt::AlignTop | Qt::AlignLeft);
  findings_ = new QLabel;
  findings_->setObjectName("verdict_findings");
  findings_->setTextFormat(Qt::RichText);  // every text from the report is escaped
  findings_->setWordWrap(true);
  findings_->setAlignment(Qt::AlignTop | Qt::AlignLeft);
  findings_scroll_ = new QScrollArea;
  findings_scroll_->setObjectName("verdict_findings_scroll");
  findings_scroll_->setFrameShape(QFrame::NoFrame);
  findings_scroll_->setWidgetResizable(true);
  findings_scroll_->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  findings_scroll_->setWidget(findings_);
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 2, 0, 2);
  layout->addWidget(level_, 0, Qt::AlignTop);
  layout->addWidget(findings_scroll_, 1);
  Clear();
}

// The findings' height at the width they have, up to kFindingLines lines.
void VerdictView::FitFindings() {
  const int scrollbar = findings_scroll_->verticalScrollBar()->sizeHint().width();
  const int width = std::max(findings_scroll_->width() - scrollbar, 50);
  const int most = findings_->fontMetrics().lineSpacing() * kFindingLines + 4;
  const int height = std::max(std::min(findings_->heightForWidth(width), most), level_->sizeHint().height());
  if (findings_scroll_->minimumHeight() != height || findings_scroll_->maximumHeight() != height)
    findings_scroll_->setFixedHeight(height);
}

void VerdictView::resizeEvent(QResizeEvent* event) {
  QWidget::resizeEvent(event);
  FitFindings();
}

void VerdictView::Show(const workflow::Verdict& verdict, const QString& stale) {
  // Stale: the mark under the level, the reason on the findings' first line.
  constexpr const char* kStaleColour = "#c86e00";  // the step list's ⟳
  level_->setText(
      QString("<span style=\"color:%1;font-size:large\"><b>Verdict: %2</b></span>")
          .arg(Colour(verdict.level), workflow::VerdictLevelName(verdict.level)) +
      (stale.isEmpty() ? QString() : QString("<br><span style=\"color:%1\"><b>⟳ stale</b></span>").arg(kStaleColour)));
  level_text_ = workflow::VerdictLevelName(verdict.level);
  stale_ = stale;
  findings_->setText((stale.isEmpty() ? QString()
                                      : QString("<span style=\"color:%1\"><b>Stale:</b></span> %2<br>")
                                            .arg(kStaleColour, Breakable(stale).toHtmlEscaped())) +
                     FindingsHtml(verdict));
  findings_->setToolTip(FindingsTooltip(verdict));
  level_->setToolTip(
      "The worst of the findings; hover over them for each figure, threshold and meaning "
      "(docs/calibration.md, \"Verdict\").");
  setVisible(true);
  FitFindings();
}

void VerdictView::Clear() {
  level_->clear();
  level_text_.clear();
  stale_.clear();
  findings_->clear();
  findings_->setToolTip(QString());
  setVisible(false);
}

QString VerdictView::LevelText() const { return level_text_; }

}  // namespace hexcal::ui
