// The Plan step and its options table: defaults < settings file < flags, one
// error style, the docs table kept true.
#include "workflow/plan_step.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/csv.h"
#include "core/noise_model.h"
#include "core/outlier_screening.h"
#include "core/robot_io.h"
#include "tests/test_support.h"

namespace hexcal::workflow {
namespace {

using hexcal::testing::ReadTextFile;
using hexcal::testing::SourceDir;
using hexcal::testing::TempDir;
using hexcal::testing::WriteTextFile;
using ::testing::HasSubstr;

PlanRequest SmallRequest(const TempDir& dir) {
  PlanRequest request;
  request.robot = "inria-left-hand";
  // Random candidates only: the boundary set's homotopy FK would cost seconds per test.
  request.planner_entries = {
      {"poses", "8"}, {"candidate_count", "300"}, {"iterations", "20"}, {"candidate_kind", "random"}};
  request.out = dir.File("plan.csv");
  return request;
}

TEST(PlanSetupOptions, DefaultsAreThePlannersAndTextRoundTrips) {
  const PlanSetup defaults;
  EXPECT_EQ(defaults.planner.num_poses, 18);
  for (const OptionSpec<PlanSetup>& spec : PlanSetupOptions()) {
    PlanSetup copy;
    const std::string text = OptionText(spec, defaults);
    ASSERT_TRUE(ApplyOptionText(spec, text, &copy, spec.key).ok()) << spec.key << " = " << text;
    EXPECT_EQ(OptionText(spec, copy), text) << spec.key;
    EXPECT_FALSE(spec.help.empty()) << spec.key;
  }
}

TEST(PlanSetupOptions, EntriesSetTheFieldsAndRefuseBadValues) {
  PlanSetup setup;
  ASSERT_TRUE(ApplyOptionEntries(PlanSetupOptions(),
                                 {{"secondary", "O4"},
                                  {"tabu", "4"},
                                  {"candidate_kind", "random,boundary"},
                                  {"continuous", "true"},
                                  {"certificate", "false"}},
                                 &setup, "flags")
                  .ok());
  EXPECT_EQ(setup.planner.secondary, Criterion::kO4);
  EXPECT_EQ(setup.planner.tabu, 4);
  EXPECT_EQ(setup.candidate_kinds, (std::vector<std::string>{"random", "boundary"}));
  EXPECT_TRUE(setup.planner.continuous);
  EXPECT_FALSE(setup.certificate);
  const auto error = [](const std::string& key, const std::string& value) {
    PlanSetup s;
    return ApplyOptionEntries(PlanSetupOptions(), {{key, value}}, &s, "plan.yaml: planner").message();
  };
  EXPECT_EQ(error("poses", "6"), "plan.yaml: planner.poses: must be at least 7 poses, got 6");
  EXPECT_EQ(error("tabu", "2.5"), "plan.yaml: planner.tabu: expected a whole number, got 2.5");
  EXPECT_EQ(error("keep", "abc"), "plan.yaml: planner.keep: expected a finite number, got 'abc'");
  EXPECT_THAT(error("criterion", "O9"), HasSubstr("expected one of O1, O2, O3, O4, D, A, E"));
  EXPECT_THAT(error("candidate_kind", "random,sphere"), HasSubstr("expected one or more of random, uniform"));
  EXPECT_THAT(error("colour", "red"), HasSubstr("planner.colour: unknown key (poses, tabu,"));
}

// docs/cli.md carries the tables the code generates: adding an option is one
// entry in the table plus this docs line.
TEST(PlanSetupOptions, DocsListEveryOption) {
  const std::string docs = ReadTextFile((SourceDir() / "docs" / "cli.md").string());
  const std::string planner = OptionsMarkdownTable(PlanSetupOptions());
  const std::string noise = OptionsMarkdownTable(NoiseModelOptions(), "noise-");
  const std::string outliers = OptionsMarkdownTable(OutlierScreeningOptions());
  EXPECT_NE(docs.find(planner), std::string::npos) << "docs/cli.md needs this table:\n" << planner;
  EXPECT_NE(docs.find(noise), std::string::npos) << "docs/cli.md needs this table:\n" << noise;
  EXPECT_NE(docs.find(outliers), std::string::npos) << "docs/cli.md needs this table:\n" << outliers;
}

TEST(PlanFromRequest, WritesThePlanAndHistory) {
  TempDir dir;
  PlanRequest request = SmallRequest(dir);
  request.history = dir.File("history.csv");
  std::vector<std::string> stages;
  JobHooks hooks;
  hooks.stage = [&](const std::string& stage) { stages.push_back(stage); };
  StatusOr<PlanOutcome> outcome = PlanFromRequest(request, hooks);
  ASSERT_TRUE(outcome.ok()) << outcome.status().message();
  EXPECT_EQ(stages, (std::vector<std::string>{"candidates", "planning", "polishing", "certificate", "prediction"}));
  StatusOr<CsvTable> plan = ReadCsv(request.out);
  ASSERT_TRUE(plan.ok());
  EXPECT_EQ(plan->rows.size(), 8u);
  EXPECT_GT(outcome->plan.final.o1, outcome->plan.initial.o1);
  // The polish starts from the finite plan and keeps the best seen: never worse.
  ASSERT_TRUE(outcome->finite_primary.has_value());
  EXPECT_GE(outcome->plan.final_primary, *outcome->finite_primary);
  EXPECT_EQ(outcome->plan.iterations, outcome->finite_iterations + 20);
  StatusOr<CsvTable> history = ReadCsv(request.history);
  ASSERT_TRUE(history.ok());
  EXPECT_EQ(history->rows.size(), static_cast<size_t>(outcome->plan.iterations + 1));
  ASSERT_TRUE(outcome->certificate.has_value());
  EXPECT_GT(outcome->certificate->d_efficiency, 0.5);
  EXPECT_GT(outcome->certificate->s_efficiency, 0.5);
  EXPECT_LE(outcome->certificate->s_efficiency, 1);
  // The certificate's best mean σ bounds the plan's own predicted σ... of the
  // weighted fit; the prediction is calibrate's unweighted one, which is no better.
  ASSERT_TRUE(outcome->prediction.valid);
  EXPECT_GE(outcome->prediction.mean_sigma, outcome->certificate->BestMeanSigma(8));
  const nlohmann::json json = ToJson(*outcome);
  EXPECT_EQ(json["poses"], 8);
  EXPECT_EQ(json["criterion"], "S");
  EXPECT_DOUBLE_EQ(json["predicted"]["mean_error"].get<double>(), outcome->prediction.mean_error);
  EXPECT_EQ(json["length_unit"], "cm");
  // Every planned pose can be reached by a straight-line controller (issue 33).
  EXPECT_TRUE(json["unreachable_from_centre"].empty()) << json["unreachable_from_centre"];
  EXPECT_NE(FormatPlanSummary(*outcome).find("moves: every pose reachable from the centre"), std::string::npos);
}

// A pose out of the strokes cannot be reached, and says why.
TEST(PlanFromRequest, UnreachablePosesNameTheirReason) {
  const Robot robot = *LoadRobot("inria-left-hand");
  const std::vector<Vector6d> poses = {(Vector6d() << 0, 0, 53.5, 0, 0, 0).finished(),
                                       (Vector6d() << 0, 0, 70, 0, 0, 0).finished()};
  const std::vector<std::string> unreachable = UnreachablePoses(robot, poses);
  ASSERT_EQ(unreachable.size(), 1u);
  EXPECT_EQ(unreachable[0].rfind("pose 2: ", 0), 0u) << unreachable[0];
}

// Flags override the settings file, which overrides the defaults.
TEST(PlanFromRequest, SettingsFileThenEntries) {
  TempDir dir;
  WriteTextFile(dir.File("plan.yaml"), "planner:\n  poses: 9\n  tabu: 2\n  certificate: false\nnoise:\n  leg: 0.002\n");
  PlanRequest request = SmallRequest(dir);
  request.settings = dir.File("plan.yaml");
  request.planner_entries = {
      {"candidate_count", "300"}, {"iterations", "10"}, {"tabu", "3"}, {"candidate_kind", "random"}};
  StatusOr<PlanOutcome> outcome = PlanFromRequest(request);
  ASSERT_TRUE(outcome.ok()) << outcome.status().message();
  EXPECT_EQ(outcome->setup.planner.num_poses, 9);
  EXPECT_EQ(outcome->setup.planner.tabu, 3);
  EXPECT_FALSE(outcome->certificate.has_value());
  WriteTextFile(dir.File("bad.yaml"), "planner:\n  tabbu: 2\n");
  request.settings = dir.File("bad.yaml");
  const Status bad = PlanFromRequest(request).status();
  EXPECT_EQ(bad.kind(), StatusKind::kBadInput);
  EXPECT_THAT(bad.message(), HasSubstr("planner.tabbu: unknown key"));
}

TEST(PlanFromRequest, ErrorKinds) {
  TempDir dir;
  PlanRequest request = SmallRequest(dir);
  request.robot = "no-such-robot";
  EXPECT_EQ(PlanFromRequest(request).status().kind(), StatusKind::kBadInput);
  request = SmallRequest(dir);
  request.candidates_file = dir.File("missing.csv");
  EXPECT_EQ(PlanFromRequest(request).status().kind(), StatusKind::kBadInput);
  request = SmallRequest(dir);
  request.planner_entries.push_back({"tabu", "8"});  // not shorter than the plan
  EXPECT_EQ(PlanFromRequest(request).status().kind(), StatusKind::kBadInput);
}

}  // namespace
}  // namespace hexcal::workflow
