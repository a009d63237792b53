// The Plan panel's camera visibility: planned poses keep the target measurable
// (its centre in the field of view, in front of the camera, seen within a
// maximum angle; core/planning_model.h, docs/planner.md). The constraints come
// from the session (the camera and target frames registered by a calibration,
// the field of view from the camera's intrinsics) or from a plan settings file
// as `hexcal plan --settings` reads it; or they are off.
//
//   auto* visibility = new VisibilityForm(session);
//   visibility->Choose("session");  // or "off", or a plan settings file
//   StatusOr<std::optional<MeasurementConstraints>> constraints = visibility->Constraints();
#pragma once

#include <QWidget>
#include <optional>

#include "core/planning_model.h"
#include "ui/session_state.h"

class QComboBox;
class QLabel;
class QLineEdit;

namespace hexcal::ui {

class VisibilityForm : public QWidget {
  Q_OBJECT
 public:
  explicit VisibilityForm(SessionState* session, QWidget* parent = nullptr);

  // The constraints chosen (none when off); an error names the file or what
  // the session lacks.
  StatusOr<std::optional<MeasurementConstraints>> Constraints() const;
  // "off", "session" or a settings file's path.
  void Choose(const QString& source);
  void Reset();

 public slots:
  void Describe();  // the summary line under the choice

 signals:
  void Chosen();  // the source or the file changed: feasibility may differ

 private:
  SessionState* session_;
  QComboBox* source_;
  QLineEdit* file_;
  QWidget* file_row_;  // the file and its browse button
  QLabel* summary_;
};

// One line: "camera at (0, 0, 150) cm, field of view 40° × 30°, view angle ≤ 60°".
QString DescribeConstraints(const MeasurementConstraints& constraints, const QString& unit);

}  // namespace hexcal::ui
