// Option descriptors (core/option_spec.h) and the errors that name an option
// by its key (Status::BadOption), for each front end to show in its words.
#include "core/option_spec.h"

#include <gtest/gtest.h>

#include <optional>
#include <string>

namespace hexcal {
namespace {

struct Settings {
  std::optional<double> wait;  // unset: the device's own
  int count = 3;
  std::string range = "8:41";
};

const OptionTable<Settings>& SettingsTable() {
  static const OptionTable<Settings> table = {
      OptionalNumberOption<Settings>("wait", "Wait", "s", 0, 600, "waited after each move", "the device's",
                                     [](Settings& s) -> std::optional<double>& { return s.wait; }),
      NumberOption<Settings>("count", "Count", OptionType::kInteger, "poses", 1, 10, "how many",
                             [](Settings& s) -> int& { return s.count; }),
      TextOption<Settings>("range", "Range", "MIN:MAX", [](Settings& s) -> std::string& { return s.range; })};
  return table;
}

TEST(Status, AnOptionsErrorNamesItByKeyAndTakesAnotherName) {
  const Status bad = Status::BadOption("settle", "must be at most 600 s, got 900");
  EXPECT_EQ(bad.kind(), StatusKind::kBadInput);
  EXPECT_EQ(bad.option(), "settle");
  EXPECT_EQ(bad.message(), "settle: must be at most 600 s, got 900");
  const Status flag = bad.WithOptionName("--settle");
  EXPECT_EQ(flag.message(), "--settle: must be at most 600 s, got 900");
  EXPECT_EQ(flag.option(), "");
  EXPECT_EQ(bad.WithHint(" (seconds)").WithOptionName("Settle time").message(),
            "Settle time: must be at most 600 s, got 900 (seconds)");
  // A failure about an option keeps its tier; a prefix ends the naming (the key is no longer first).
  const Status failed = Status::Failed("only 5 poses").AboutOption("init");
  EXPECT_EQ(failed.kind(), StatusKind::kFailed);
  EXPECT_EQ(failed.WithOptionName("Initial set").message(), "Initial set: only 5 poses");
  EXPECT_EQ(bad.AsFailure().option(), "settle");
  EXPECT_EQ(bad.Prefixed("plan.yaml: ").option(), "");
  EXPECT_EQ(bad.Prefixed("plan.yaml: ").WithOptionName("--settle").message(),
            "plan.yaml: settle: must be at most 600 s, got 900");
  // Any other error has no option to rename.
  EXPECT_EQ(Status::BadInput("settle: x").WithOptionName("--settle").message(), "settle: x");
  EXPECT_TRUE(Status::Ok().AboutOption("settle").ok());
}

TEST(CheckOptionRanges, NamesTheOptionByKey) {
  Settings settings;
  EXPECT_TRUE(CheckOptionRanges(SettingsTable(), settings).ok());  // wait unset: the device's
  settings.wait = 900;
  const Status wait = CheckOptionRanges(SettingsTable(), settings);
  EXPECT_EQ(wait.option(), "wait");
  EXPECT_EQ(wait.message(), "wait: must be at most 600 s, got 900");
  settings.wait = 0;
  settings.count = 0;
  EXPECT_EQ(CheckOptionRanges(SettingsTable(), settings).message(), "count: must be at least 1 poses, got 0");
  // The same words as the text of a flag, a file or a form row.
  EXPECT_EQ(ApplyOptionText(SettingsTable()[1], "0", &settings, "--count").message(),
            "--count: must be at least 1 poses, got 0");
}

TEST(OptionSpec, AnOptionalNumberAndText) {
  const OptionSpec<Settings>& wait = SettingsTable()[0];
  const OptionSpec<Settings>& range = SettingsTable()[2];
  Settings settings;
  EXPECT_FALSE(OptionIsSet(wait, settings));
  EXPECT_EQ(OptionText(wait, settings), "");
  ASSERT_TRUE(ApplyOptionText(wait, "0.5", &settings, "wait").ok());
  EXPECT_EQ(settings.wait, 0.5);
  EXPECT_EQ(OptionText(wait, settings), "0.5");
  // Text is taken as it is; the step that reads it checks its form.
  ASSERT_TRUE(ApplyOptionText(range, "8-41", &settings, "range").ok());
  EXPECT_EQ(OptionText(range, settings), "8-41");
  // The docs say what applies when an optional number is not given.
  EXPECT_EQ(OptionsMarkdownTable(SettingsTable()),
            "| key | flag | type | unit | range | default | meaning |\n|---|---|---|---|---|---|---|\n"
            "| `wait` | `--wait` | number | s | 0 – 600 | the device's | waited after each move |\n"
            "| `count` | `--count` | integer | poses | 1 – 10 | 3 | how many |\n"
            "| `range` | `--range` | text |  |  | 8:41 | MIN:MAX |\n");
}

}  // namespace
}  // namespace hexcal
