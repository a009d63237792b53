// The study kept in the session (session_study.h) and its section of the HTML
// report (study_report_section.h), on a demo session of random poses: the
// study/ folder is published whole and read back as the run made it (the
// record, every subset's values); --no-save leaves it alone; an input changed
// since marks it stale, in the reader and in red in the report; a study.json
// that does not match its subsets.csv is refused by name.
#include "session/session_study.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <future>
#include <thread>

#include "core/session.h"
#include "report/session_report.h"
#include "report/study_report_section.h"
#include "tests/test_support.h"
#include "workflow/demo.h"
#include "workflow/session_edits.h"
#include "workflow/study_step.h"
#include "workflow/tests/test_sessions.h"

namespace hexcal::workflow {
namespace {

namespace fs = std::filesystem;
using hexcal::testing::ReadTextFile;
using hexcal::testing::TempDir;
using hexcal::testing::WriteTextFile;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;

class KeptStudy : public DemoSessionSuite<KeptStudy> {
 public:
  static DemoRequest Request() { return RandomPosesDemo(/*poses=*/14, /*seed=*/3); }

 protected:
  // A fresh copy of the demo session, so that a test may change it.
  std::string CopyOfSession() {
    const std::string copy = temp_.File("session");
    fs::copy(Session(), copy, fs::copy_options::recursive);
    return copy;
  }
  static StudyRequest SmallStudy(const std::string& session) {
    StudyRequest request;
    request.session = session;
    request.study.select = 8;
    request.study.subsets = 30;
    request.study.seed = 5;
    return request;
  }
  // SmallStudy with --no-save.
  static StudyRequest UnsavedStudy(const std::string& session) {
    StudyRequest request = SmallStudy(session);
    request.save = false;
    return request;
  }

  TempDir temp_;
};

TEST_F(KeptStudy, IsPublishedWholeAndReadBackAsTheRunMadeIt) {
  const std::string session = CopyOfSession();
  ASSERT_FALSE(HasSessionStudy(session));
  StatusOr<StudyOutcome> run = RunStudy(SmallStudy(session));
  ASSERT_TRUE(run.ok()) << run.status().message();
  EXPECT_EQ(run->saved, StudyFolderPath(session));
  EXPECT_THAT(FormatStudySummary(*run), HasSubstr("study kept in " + StudyFolderPath(session)));
  ASSERT_TRUE(HasSessionStudy(session));
  for (const char* stem : {"fig18_o1", "fig18_o2", "fig18_o3", "fig18_o4", "fig19_position", "fig19_orientation"}) {
    EXPECT_THAT(ReadTextFile(StudyFolderPath(session) + "/" + stem + ".svg"), HasSubstr("</svg>")) << stem;
    EXPECT_TRUE(fs::exists(StudyFolderPath(session) + "/" + stem + ".png")) << stem;
  }
  for (const auto& entry : fs::directory_iterator(session))  // no staging folder left behind
    EXPECT_THAT(entry.path().filename().string(), Not(HasSubstr(".new-")));

  StatusOr<SessionStudy> kept = LoadSessionStudy(session);
  ASSERT_TRUE(kept.ok()) << kept.status().message();
  EXPECT_FALSE(kept->Stale()) << ListNames(kept->changed_inputs);
  EXPECT_EQ(ToJson(kept->record), ToJson(*run));  // what --json prints is what the session keeps
  EXPECT_EQ(kept->record.inputs.count("legs.csv"), 1u);
  for (SubsetMetric metric : kSubsetMetrics) {
    const std::vector<double> values = RandomValues(run->result, metric);
    ASSERT_EQ(kept->RandomValuesOf(metric).size(), values.size()) << SubsetMetricName(metric);
    for (size_t k = 0; k < values.size(); ++k) EXPECT_EQ(kept->RandomValuesOf(metric)[k], values[k]);
  }
}

TEST_F(KeptStudy, RecordRoundTripsThroughItsJson) {
  const std::string session = CopyOfSession();
  StudyRequest request = SmallStudy(session);
  request.study.secondary = Criterion::kO4;
  request.weighted_selection = false;
  StatusOr<StudyOutcome> run = RunStudy(request);
  ASSERT_TRUE(run.ok()) << run.status().message();
  const StudyRecord record = MakeStudyRecord(*run);
  StatusOr<StudyRecord> back = StudyRecordFromJson(ToJson(record), "study.json");
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(ToJson(*back), ToJson(record));
  EXPECT_EQ(back->secondary, Criterion::kO4);
  EXPECT_FALSE(back->weighted_selection);
  EXPECT_THAT(StudyRankSentence(*back), HasSubstr("validates better than"));

  nlohmann::json wrong = ToJson(record);
  wrong["selected"]["images"].push_back("extra.png");
  EXPECT_THAT(StudyRecordFromJson(wrong, "study.json").status().message(),
              HasSubstr("study.json: key 'selected.images': expected one image per pose"));
  wrong = ToJson(record);
  wrong["format"] = 2;
  EXPECT_THAT(StudyRecordFromJson(wrong, "study.json").status().message(), HasSubstr("format 2 is not 1"));
}

TEST_F(KeptStudy, NoSaveLeavesTheSessionAlone) {
  const std::string session = CopyOfSession();
  StatusOr<StudyOutcome> run = RunStudy(UnsavedStudy(session));
  ASSERT_TRUE(run.ok()) << run.status().message();
  EXPECT_TRUE(run->saved.empty());
  EXPECT_FALSE(fs::exists(StudyFolderPath(session)));
  EXPECT_TRUE(ToJson(*run)["saved"].is_null());
}

// Another writer holds the session: nothing is written, and the caller hears "busy".
TEST_F(KeptStudy, IsNotWrittenWhileAnotherWriterHoldsTheSession) {
  const std::string session = CopyOfSession();
  StatusOr<StudyOutcome> run = RunStudy(UnsavedStudy(session));
  ASSERT_TRUE(run.ok()) << run.status().message();
  std::promise<bool> locked;
  std::promise<void> release;
  std::thread writer([&] {  // the lock is re-entrant per thread: another thread is another writer
    StatusOr<SessionLock> lock = SessionLock::Acquire(session, LockWait::kNo);
    locked.set_value(lock.ok());
    release.get_future().wait();
  });
  EXPECT_TRUE(locked.get_future().get());
  const Status saved = SaveSessionStudy(&*run, LockWait::kNo);
  release.set_value();
  writer.join();
  EXPECT_EQ(saved.kind(), StatusKind::kBusy) << saved.message();
  EXPECT_FALSE(fs::exists(StudyFolderPath(session)));
  EXPECT_TRUE(run->saved.empty());
  ASSERT_TRUE(SaveSessionStudy(&*run, LockWait::kNo).ok());  // free again
  EXPECT_TRUE(HasSessionStudy(session));
}

TEST_F(KeptStudy, ChangedInputsMakeItStaleAndTheReportSaysSo) {
  const std::string session = CopyOfSession();
  EXPECT_EQ(StudyReportSection(session), "");  // no study, no section
  ASSERT_TRUE(RunStudy(SmallStudy(session)).ok());
  const std::string fresh = StudyReportSection(session);
  // Pages hold whole SVGs: checked by find, so that a failure does not print them.
  for (const char* text :
       {"<h2 id=\"study\">Section 8 study</h2>", "validates better than", "held-out position RMS (cm)"})
    EXPECT_NE(fresh.find(text), std::string::npos) << text;
  EXPECT_EQ(fresh.find("Stale study"), std::string::npos);
  size_t charts = 0;
  for (size_t at = fresh.find("<svg"); at != std::string::npos; at = fresh.find("<svg", at + 1)) ++charts;
  EXPECT_EQ(charts, 6u);  // Figs. 19 (two) and 18 (four)
  StatusOr<std::string> page = SessionReportHtml(session);
  ASSERT_TRUE(page.ok()) << page.status().message();
  EXPECT_NE(page->find("<h2 id=\"study\">Section 8 study</h2>"), std::string::npos);

  // One reading moved by 1 µm: the study no longer describes the session.
  StatusOr<std::vector<LegsRow>> rows = LoadSessionLegs(session);
  ASSERT_TRUE(rows.ok());
  const LegsRow& row = rows->front();
  const EditOutcome edited =
      ApplyLegsEdit(session, LegsEdit::SetReading(row.image, 0, row.legs[0], row.legs[0] + 1e-4));
  ASSERT_TRUE(edited.status.ok() && !edited.conflict) << edited.status.message() << edited.conflict_text;
  StatusOr<SessionStudy> kept = LoadSessionStudy(session);
  ASSERT_TRUE(kept.ok()) << kept.status().message();
  EXPECT_THAT(kept->changed_inputs, ElementsAre("legs.csv"));
  const std::string stale = StudyReportSection(session);
  EXPECT_NE(stale.find("<b>Stale study.</b> legs.csv changed after this study was made"), std::string::npos);
}

TEST_F(KeptStudy, SubsetsThatDoNotMatchTheRecordAreRefused) {
  const std::string session = CopyOfSession();
  ASSERT_TRUE(RunStudy(SmallStudy(session)).ok());
  const std::string csv = StudyFolderPath(session) + "/subsets.csv";
  std::string text = ReadTextFile(csv);
  text.erase(text.rfind('\n', text.size() - 2) + 1);  // the last subset's row
  WriteTextFile(csv, text);
  StatusOr<SessionStudy> kept = LoadSessionStudy(session);
  ASSERT_FALSE(kept.ok());
  EXPECT_THAT(kept.status().message(), HasSubstr("subsets.csv: 30 rows, study.json has 30 random subsets"));
  EXPECT_THAT(StudyReportSection(session), HasSubstr("subsets.csv: 30 rows"));  // a section with the error
}

}  // namespace
}  // namespace hexcal::workflow
