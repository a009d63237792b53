// hexcal plan --robot R --poses N [--candidates FILE | --candidate-kind K [--candidate-count W]]...
//   [--init random|uniform|boundary|FILE] [--continuous] [--criterion O1] [--secondary O4 --keep 0.8]
//   [--tabu n --iterations K] [--addfind-starts U] [--noise-position p --noise-angle a --noise-leg l]
//   [--settings plan.yaml] [--seed S] --out plan.csv [--history history.csv] [--json]
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "app/commands/plan_io.h"
#include "core/candidates.h"
#include "core/csv.h"
#include "core/ioops.h"
#include "core/optimal_design.h"
#include "core/robot_io.h"

namespace hexcal::cli {
namespace {

struct PlanCliOptions {
  std::string robot, candidates_file, init = "random", criterion = "O1", secondary, settings, out, history;
  std::vector<std::string> candidate_kinds;
  int poses = 18, candidate_count = 0, certificate_seconds = 60;
  std::vector<double> noise;  // position, angle, leg
  double noise_position = -1, noise_angle = -1, noise_leg = -1;
  bool json = false, no_certificate = false;
  PlannerOptions planner;
};

StatusOr<PlanningModel> BuildModel(const PlanCliOptions& cli) {
  StatusOr<Robot> robot = LoadRobot(cli.robot);
  if (!robot.ok()) return robot.status();
  PlanningModel model{*robot, std::nullopt, std::nullopt};
  if (!cli.settings.empty()) {
    StatusOr<PlanSettings> settings = LoadPlanSettings(cli.settings, *robot);
    if (!settings.ok()) return settings.status();
    model.noise = settings->noise;
    model.measurement = settings->measurement;
  }
  if (cli.noise_position >= 0 || cli.noise_angle >= 0 || cli.noise_leg >= 0) {
    NoiseModel noise = model.noise.value_or(NoiseModel{});
    if (cli.noise_position >= 0) noise.position = cli.noise_position;
    if (cli.noise_angle >= 0) noise.angle_deg = cli.noise_angle;
    if (cli.noise_leg >= 0) noise.leg = cli.noise_leg;
    model.noise = noise;
  }
  return model;
}

int RunPlan(PlanCliOptions cli, std::ostream& out, std::ostream& err) {
  StatusOr<PlanningModel> model = BuildModel(cli);
  if (!model.ok()) return ReportError(err, "plan", model.status());
  const std::optional<Criterion> criterion = ParseCriterion(cli.criterion);
  if (!criterion) return ReportError(err, "plan", Status::Error("--criterion: '" + cli.criterion + "' is not O1, O2, O3, O4, D, A or E"));
  cli.planner.criterion = *criterion;
  if (!cli.secondary.empty()) {
    cli.planner.secondary = ParseCriterion(cli.secondary);
    if (!cli.planner.secondary) return ReportError(err, "plan", Status::Error("--secondary: '" + cli.secondary + "' is not a criterion"));
  }
  cli.planner.num_poses = cli.poses;
  std::string error;
  if (!cli.planner.IsValid(&error)) return ReportError(err, "plan", Status::Error(error));

  // A file the user named that is wrong is bad input (2); a generated set that
  // cannot be had is a failed computation (1).
  StatusOr<std::vector<Vector6d>> initial = InitialPoses(*model, cli.init, cli.poses, cli.planner.seed);
  if (!initial.ok()) {
    return ReportError(err, "plan", initial.status(), ParseCandidateKind(cli.init) ? kExitFailure : kExitBadInput);
  }
  ProgressBar candidates_progress("candidates");
  StatusOr<CandidatePool> pool = BuildCandidatePool(*model, cli.candidates_file, cli.candidate_kinds,
                                                    cli.candidate_count, cli.planner.continuous, cli.planner.seed,
                                                    [&](int done, int total) { candidates_progress.Update(done, total); });
  if (!pool.ok()) return ReportError(err, "plan", pool.status(), cli.candidates_file.empty() ? kExitFailure : kExitBadInput);

  ProgressBar progress("planning");
  StatusOr<PlanResult> plan = PlanPoses(*model, pool->poses, *initial, cli.planner,
                                        {[&](int iteration, int budget) { progress.Update(iteration, budget); }});
  if (!plan.ok()) return ReportError(err, "plan", plan.status(), kExitFailure);

  nlohmann::json certificate;
  if (!cli.planner.continuous && !cli.no_certificate) {
    OptimalDesignOptions design_options;
    design_options.max_seconds = cli.certificate_seconds;
    StatusOr<PlanCertificate> cert = CertifyPlan(*model, pool->poses, plan->poses, design_options);
    if (!cert.ok()) return ReportError(err, "plan", cert.status(), kExitFailure);
    certificate = {{"d_efficiency", cert->d_efficiency}, {"gap", cert->design.gap},
                   {"design_converged", cert->design.converged}, {"design_support", cert->design.support},
                   {"design_iterations", cert->design.iterations}};
  }
  if (Status s = WritePlanCsv(cli.out, *model, plan->poses); !s.ok()) return ReportError(err, "plan", s, kExitFailure);
  if (!cli.history.empty()) {
    if (Status s = WriteHistoryCsv(cli.history, *plan); !s.ok()) return ReportError(err, "plan", s, kExitFailure);
  }
  const nlohmann::json summary = PlanSummaryJson(cli.planner, *plan, *pool, certificate, cli.out);
  if (cli.json) {
    out << summary.dump(2) << "\n";
  } else {
    PrintPlanSummary(summary, out);
  }
  return kExitOk;
}

}  // namespace

void AddPlanCommand(CLI::App& app, int* exit_code) {
  auto o = std::make_shared<PlanCliOptions>();
  CLI::App* sub = app.add_subcommand("plan", "choose N measurement poses (IOOPS, paper section 4)");
  sub->add_option("--robot", o->robot, "robot file or preset name")->required();
  sub->add_option("--poses", o->poses, "N, poses in the plan")->capture_default_str();
  auto* file = sub->add_option("--candidates", o->candidates_file, "candidate pose CSV (x,y,z,q1,q2,q3)");
  sub->add_option("--candidate-kind", o->candidate_kinds, "random | uniform | boundary; repeat to pool sets")
      ->excludes(file);
  sub->add_option("--candidate-count", o->candidate_count,
                  "poses per random/uniform set (default 10000, continuous 2000)");
  sub->add_option("--init", o->init, "initial N poses: random | uniform | boundary | a pose CSV")->capture_default_str();
  sub->add_flag("--continuous", o->planner.continuous, "AddFind by SLSQP in the workspace (candidates are the starts)");
  sub->add_option("--criterion", o->criterion, "O1 | O2 | O3 | O4 | D | A | E")->capture_default_str();
  sub->add_option("--secondary", o->secondary, "secondary criterion (section 6.2)");
  sub->add_option("--keep", o->planner.keep, "fraction of AddFind results kept on the primary")->capture_default_str();
  sub->add_option("--tabu", o->planner.tabu, "Tabu list length n (section 4.3)")->capture_default_str();
  sub->add_option("--iterations", o->planner.iterations, "iteration budget (default 200 with Tabu, else 10 N)");
  sub->add_option("--addfind-starts", o->planner.addfind_starts, "U (default: all candidates; continuous 40)");
  sub->add_option("--switch-probability", o->planner.criterion_switch_probability,
                  "section 4.2: AddFind uses the secondary with this probability")->capture_default_str();
  sub->add_option("--removal-choices", o->planner.removal_choices, "section 4.2: remove one of the r best at random")
      ->capture_default_str();
  sub->add_option("--noise-position", o->noise_position, "weight rows by the noise: position half-width (robot unit)");
  sub->add_option("--noise-angle", o->noise_angle, "angle half-width (degrees)");
  sub->add_option("--noise-leg", o->noise_leg, "leg reading half-width (robot unit)");
  sub->add_option("--settings", o->settings, "plan settings YAML (noise, camera visibility); docs/planner.md");
  sub->add_option("--seed", o->planner.seed, "random seed")->capture_default_str();
  sub->add_option("--threads", o->planner.threads, "scoring threads (0: every core)")->capture_default_str();
  sub->add_flag("--no-certificate", o->no_certificate, "skip the D-optimal design bound");
  sub->add_option("--certificate-seconds", o->certificate_seconds, "time limit of the design bound")->capture_default_str();
  sub->add_option("--out", o->out, "plan CSV: x,y,z,q1,q2,q3,L1..L6")->required();
  sub->add_option("--history", o->history, "indices per iteration CSV (figs 6, 10-12)");
  sub->add_flag("--json", o->json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunPlan(*o, std::cout, std::cerr); });
}

}  // namespace hexcal::cli
