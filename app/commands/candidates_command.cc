// hexcal candidates --robot R --kind random|uniform|boundary [--count W] [--seed S] --out C.csv [--force] [--json]
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "core/candidates.h"
#include "core/csv.h"
#include "core/robot_io.h"

namespace hexcal::cli {
namespace {

struct CandidatesCliOptions {
  std::string robot, kind = "random", out;
  int count = 1000;
  uint64_t seed = 1;
  bool force = false, json = false;
};

int RunCandidates(const CandidatesCliOptions& cli, std::ostream& out, std::ostream& err) {
  if (Status s = CheckOutputFree(cli.out, cli.force); !s.ok()) return ReportError(err, "candidates", s);
  StatusOr<Robot> robot = LoadRobot(cli.robot);
  if (!robot.ok()) return ReportError(err, "candidates", robot.status());
  const std::optional<CandidateKind> kind = ParseCandidateKind(cli.kind);
  if (!kind) {
    return ReportError(err, "candidates",
                       Status::BadInput("--kind: '" + cli.kind + "' is not random, uniform or boundary"));
  }
  CandidateOptions options;
  options.kind = *kind;
  options.count = cli.count;
  options.seed = cli.seed;
  std::string error;
  if (!options.IsValid(&error)) return ReportError(err, "candidates", Status::BadInput(error));

  ProgressBar progress(std::string("candidates (") + cli.kind + ")");
  StatusOr<CandidateSet> set =
      GenerateCandidates(*robot, options, {[&](int done, int total) { progress.Update(done, total); }});
  if (!set.ok()) return ReportError(err, "candidates", set.status());

  std::vector<std::vector<std::string>> rows;
  for (const Vector6d& v : set->poses) {
    std::vector<std::string> row;
    for (int k = 0; k < 6; ++k) row.push_back(FormatNumber(v[k]));
    rows.push_back(row);
  }
  if (Status s = WriteCsv(cli.out, {"x", "y", "z", "q1", "q2", "q3"}, rows); !s.ok()) {
    return ReportError(err, "candidates", s);
  }
  if (cli.json) {
    nlohmann::json j = {{"count", set->poses.size()}, {"kind", cli.kind}, {"out", cli.out}, {"draws", set->draws}};
    if (*kind == CandidateKind::kBoundary)
      j["real_modes"] = set->real_modes;
    else
      j["seed"] = cli.seed;
    out << JsonText(j);
  } else {
    out << set->poses.size() << " " << cli.kind << " candidate poses written to " << cli.out;
    if (*kind == CandidateKind::kBoundary) {
      out << " (64 min/max leg combinations, " << set->real_modes << " real assembly modes, " << set->poses.size()
          << " feasible)";
    } else {
      out << " (" << set->draws << " drawn, acceptance " << 100.0 * set->poses.size() / std::max<int64_t>(1, set->draws)
          << " %)";
    }
    out << "\n";
  }
  return kExitOk;
}

}  // namespace

void AddCandidatesCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<CandidatesCliOptions>();
  CLI::App* sub = app.add_subcommand("candidates", "generate candidate measurement poses");
  sub->add_option("--robot", options->robot, "robot file or preset name")->required();
  sub->add_option("--kind", options->kind, "random | uniform | boundary")->capture_default_str();
  sub->add_option("--count", options->count, "number of poses (random, uniform)")
      ->check(CountRange(1, kMaxCandidateCount, "a pose CSV of about 700 MB"))
      ->capture_default_str();
  sub->add_option("--seed", options->seed, "random seed / sequence offset")->capture_default_str();
  sub->add_option("--out", options->out, "output pose CSV")->required();
  sub->add_flag("--force", options->force, "overwrite --out if it exists");
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunCandidates(*options, std::cout, std::cerr); });
}

}  // namespace hexcal::cli
