#include "ui/verdict_view.h"

#include <QHBoxLayout>
#include <QLabel>

namespace hexcal::ui {
namespace {

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
                .arg(Colour(f.level), workflow::VerdictLevelName(f.level), Html(f.aspect), Html(f.advice));
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
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 2, 0, 2);
  layout->addWidget(level_);
  layout->addWidget(findings_, 1);
  Clear();
}

void VerdictView::Show(const workflow::Verdict& verdict) {
  level_->setText(QString("<span style=\"color:%1;font-size:large\"><b>Verdict: %2</b></span>")
                      .arg(Colour(verdict.level), workflow::VerdictLevelName(verdict.level)));
  level_text_ = workflow::VerdictLevelName(verdict.level);
  findings_->setText(FindingsHtml(verdict));
  findings_->setToolTip(FindingsTooltip(verdict));
  level_->setToolTip(
      "The worst of the findings; hover over them for each figure, threshold and meaning "
      "(docs/calibration.md, \"Verdict\").");
  setVisible(true);
}

void VerdictView::Clear() {
  level_->clear();
  level_text_.clear();
  findings_->clear();
  findings_->setToolTip(QString());
  setVisible(false);
}

QString VerdictView::LevelText() const { return level_text_; }

}  // namespace hexcal::ui
