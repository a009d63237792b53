#include "workflow/study_step.h"

#include <chrono>

#include "charts/chart_render.h"
#include "core/calibration_file.h"
#include "core/parallel.h"
#include "session/session_study.h"
#include "workflow/session_calibrate.h"

namespace hexcal::workflow {
namespace {

Status CheckFiguresFree(const StudyRequest& request) {
  if (request.plots.empty()) return Status::Ok();
  std::vector<std::string> stems;
  for (SubsetMetric metric : kSubsetMetrics) stems.push_back(StudyFigureStem(metric));
  return charts::CheckChartFilesFree(request.plots, stems, request.force);
}

// --plots DIR: the figures, DIR created if missing.
Status WritePlots(StudyOutcome* outcome) {
  const std::string& directory = outcome->request.plots;
  if (Status s = charts::CreatePlotsFolder(directory); !s.ok()) return s;
  return WriteStudyFigures(*outcome, directory, &outcome->figures);
}

}  // namespace

StatusOr<StudyOutcome> RunStudy(StudyRequest request, const JobHooks& hooks) {
  const auto start = std::chrono::steady_clock::now();
  if (Status s = request.study.Check(); !s.ok()) return s;
  if (Status s = CheckFiguresFree(request); !s.ok()) return s;
  StatusOr<MeasuredSession> session = LoadMeasuredSession(request.session, request.wait, hooks);
  if (!session.ok()) return session.status();
  // calibrate --session's fit, without the outlier screening: each subset is
  // the paper's plain least squares, and 13 rows leave little to screen with.
  request.study.calibration = SessionCalibrationOptions(session->noise, OutlierScreening{});
  if (request.weighted_selection) request.study.selection_noise = session->noise;

  const auto subsets_start = std::chrono::steady_clock::now();
  StatusOr<SubsetStudyResult> result = RunSubsetStudy(session->nominal, session->measurements, request.study, hooks);
  if (!result.ok()) return result.status();  // bad options are bad input, a failed study a failure
  StudyOutcome outcome;
  outcome.subsets_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - subsets_start).count();
  outcome.request = request;
  outcome.robot = session->nominal.name;
  outcome.length_unit = LengthUnitName(session->nominal.length_unit);
  outcome.images = session->images;
  outcome.unusable = session->unusable;
  outcome.result = std::move(*result);
  outcome.metrics = SummarizeMetrics(outcome.result);
  outcome.threads = ParallelWorkers(request.study.subsets + 1, request.study.num_threads);
  outcome.inputs = std::move(session->inputs);
  if (!request.plots.empty()) {
    if (Status s = WritePlots(&outcome); !s.ok()) return s;
  }
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  outcome.created = CurrentUtcTimestamp();
  if (request.save) {
    // A study of minutes is not thrown away for a writer holding the lock a moment.
    const LockWait wait = request.wait == LockWait::kForever ? LockWait::kForever : LockWait::kBriefly;
    if (Status s = SaveSessionStudy(&outcome, wait); !s.ok()) return s;
  }
  return outcome;
}

}  // namespace hexcal::workflow
