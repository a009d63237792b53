// The scroll area each panel sits in (MainWindow): whatever a panel holds, it
// cannot make the window taller or wider than the screen. The panel fills
// the area, and is made larger (and scrolls) only when its minimum size does
// not fit. QScrollArea's own widgetResizable gives a panel with word-wrapped
// labels its *preferred* height for the width (heightForWidth: every table
// and chart at its preferred size), which made panels scroll that fit; that
// the labels get the lines they need is the layout's work, and
// ui/tests/fit_test.cc checks it at 1024×600 and 1280×720 (issue 35).
//
//   auto* scroll = new PanelScroll(panel);
//   stack->addWidget(scroll);
#pragma once

#include <QScrollArea>

namespace hexcal::ui {

class PanelScroll : public QScrollArea {
  Q_OBJECT
 public:
  explicit PanelScroll(QWidget* panel, QWidget* parent = nullptr);

 protected:
  void resizeEvent(QResizeEvent* event) override;
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  void FitPanel();
};

}  // namespace hexcal::ui
