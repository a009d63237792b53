// The Qt and Qt Charts classes the step panels' headers name, declared once,
// as <iosfwd> declares the streams; and BackgroundJob, the worker of every
// panel that runs one. A panel's header only holds pointers to its widgets,
// which need the name and not the class: including <QTableWidget> or
// <QChartView> there would compile them into every file that includes a
// panel. A panel's .cc includes the classes it makes.
//
//   #include "ui/qt_fwd.h"
//   class StudyView : public QWidget {
//     QTableWidget* table_;
//     QtCharts::QChartView* chart_;
//     BackgroundJob* job_;
//   };
#pragma once

class QCheckBox;
class QComboBox;
class QGridLayout;
class QLabel;
class QLayout;
class QListWidget;
class QPlainTextEdit;
class QProgressBar;
class QPushButton;
class QSlider;
class QSplitter;
class QStackedWidget;
class QTabWidget;
class QTableWidget;
class QTableWidgetItem;
class QTimer;

namespace QtCharts {
class QChartView;
}

namespace hexcal::ui {
class BackgroundJob;
}
