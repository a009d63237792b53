#include "ui/run_log.h"

#include <QFontDatabase>
#include <QPlainTextEdit>
#include <QToolButton>
#include <QVBoxLayout>

namespace hexcal::ui {
namespace {

// Most of the calibration summary's lines, within a 1024×600 window; the rest scroll.
constexpr int kLogLines = 6;

}  // namespace

RunLog::RunLog(QWidget* parent) : QWidget(parent) {
  setObjectName("run_log");
  toggle_ = new QToolButton;
  toggle_->setObjectName("run_log_toggle");
  toggle_->setText("Run log");
  toggle_->setToolTip("The lines the last run printed (as the command line prints them)");
  toggle_->setCheckable(true);
  toggle_->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
  toggle_->setAutoRaise(true);
  text_ = new QPlainTextEdit;
  text_->setObjectName("run_log_text");
  text_->setReadOnly(true);
  text_->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
  text_->setLineWrapMode(QPlainTextEdit::WidgetWidth);  // a path-long line wraps, no sideways scrolling
  text_->setFixedHeight(text_->fontMetrics().lineSpacing() * kLogLines + 12);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(2);
  layout->addWidget(toggle_, 0, Qt::AlignLeft);
  layout->addWidget(text_);
  connect(toggle_, &QToolButton::toggled, this, &RunLog::SetExpanded);
  SetText({});
}

void RunLog::SetText(const QString& text) {
  text_->setPlainText(text);
  toggle_->setEnabled(!text.isEmpty());
  if (text.isEmpty()) SetExpanded(false);
}

QString RunLog::Text() const { return text_->toPlainText(); }

void RunLog::SetExpanded(bool expanded) {
  toggle_->setChecked(expanded);
  toggle_->setArrowType(expanded ? Qt::DownArrow : Qt::RightArrow);
  text_->setVisible(expanded);
}

bool RunLog::Expanded() const { return toggle_->isChecked(); }

}  // namespace hexcal::ui
