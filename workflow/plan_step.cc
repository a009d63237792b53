#include "workflow/plan_step.h"

#include <algorithm>
#include <iomanip>
#include <limits>
#include <random>
#include <sstream>

#include "core/candidates.h"
#include "core/csv.h"
#include "core/inverse_kinematics.h"
#include "core/robot_io.h"
#include "core/straight_moves.h"
#include "devices/controller.h"
#include "workflow/session_plan_model.h"

namespace hexcal::workflow {
namespace {

StatusOr<CandidateSet> Generate(const Robot& robot, CandidateKind kind, int count, uint64_t seed,
                                const JobHooks& hooks) {
  CandidateOptions options;
  options.kind = kind;
  options.count = count;
  options.seed = seed;
  return GenerateCandidates(robot, options, hooks);
}

nlohmann::json IndicesOnly(const ObservabilityIndices& o) {
  return {{"O1", o.o1}, {"O2", o.o2}, {"O3", o.o3}, {"O4", o.o4}};
}

}  // namespace

StatusOr<CandidatePool> BuildCandidatePool(const PlanningModel& model, const std::string& file,
                                           const std::vector<std::string>& kinds, int count, bool continuous,
                                           uint64_t seed, const JobHooks& hooks) {
  CandidatePool pool;
  pool.sources = nlohmann::json::array();
  std::vector<Vector6d> raw;
  if (!file.empty()) {
    StatusOr<std::vector<Vector6d>> poses = LoadPoses(file);
    if (!poses.ok()) return poses.status();
    raw = *poses;
    pool.sources.push_back({{"kind", "file"}, {"path", file}, {"count", raw.size()}});
  } else {
    const std::vector<std::string> names = kinds.empty() ? std::vector<std::string>{"random"} : kinds;
    const int per_set = count > 0 ? count : (continuous ? 2000 : 10000);
    for (size_t k = 0; k < names.size(); ++k) {
      const std::optional<CandidateKind> kind = ParseCandidateKind(names[k]);
      if (!kind) return Status::BadOption("candidate_kind", "'" + names[k] + "' is not random, uniform or boundary");
      StatusOr<CandidateSet> set = Generate(model.robot, *kind, per_set, seed + 7919 * k, hooks);
      if (!set.ok()) return set.status();
      raw.insert(raw.end(), set->poses.begin(), set->poses.end());
      pool.sources.push_back({{"kind", names[k]}, {"count", set->poses.size()}});
    }
  }
  const std::vector<char> feasible = model.FeasibleOf(raw);
  for (size_t j = 0; j < raw.size(); ++j) {
    if (feasible[j]) pool.poses.push_back(raw[j]);
  }
  if (pool.poses.empty() && !file.empty()) {
    return Status::BadInput(file + ": none of its " + std::to_string(raw.size()) +
                            " poses satisfies the robot and measurement constraints (all unreachable)");
  }
  if (pool.poses.empty()) return Status::Failed("no candidate pose satisfies the robot and measurement constraints");
  return pool;
}

StatusOr<std::vector<Vector6d>> InitialPoses(const PlanningModel& model, const std::string& init, int count,
                                             uint64_t seed) {
  const std::optional<CandidateKind> kind = ParseCandidateKind(init);
  std::vector<Vector6d> poses;
  if (!kind) {
    StatusOr<std::vector<Vector6d>> file = LoadPoses(init);
    if (!file.ok()) return file.status().AboutOption("init");
    poses = *file;
    if (static_cast<int>(poses.size()) != count) {
      return Status::BadOption("init", "'" + init + "' has " + std::to_string(poses.size()) + " poses; the plan has " +
                                           std::to_string(count));
    }
    return poses;
  }
  // Generated sets are drawn with another seed than the candidates, so they differ;
  // poses that break a measurement constraint are skipped.
  for (int attempt = 0; attempt < 8 && static_cast<int>(poses.size()) < count; ++attempt) {
    const int want = *kind == CandidateKind::kBoundary ? 0 : (count - static_cast<int>(poses.size())) << attempt;
    StatusOr<CandidateSet> set = Generate(model.robot, *kind, std::max(want, 1), seed + 104729 * (attempt + 1), {});
    if (!set.ok()) return set.status();
    std::vector<Vector6d> feasible;
    std::copy_if(set->poses.begin(), set->poses.end(), std::back_inserter(feasible),
                 [&](const Vector6d& pose) { return model.IsFeasible(pose); });
    if (*kind == CandidateKind::kBoundary) {
      std::mt19937_64 rng(seed);
      std::shuffle(feasible.begin(), feasible.end(), rng);
      poses = feasible;
      break;
    }
    poses.insert(poses.end(), feasible.begin(), feasible.end());
  }
  if (static_cast<int>(poses.size()) < count) {
    return Status::Failed(init + ": only " + std::to_string(poses.size()) +
                          " poses satisfy the robot and measurement constraints, fewer than the " +
                          std::to_string(count) + " asked")
        .AboutOption("init");
  }
  poses.resize(count);
  return poses;
}

Status WritePlanCsv(const std::string& path, const PlanningModel& model, const std::vector<Vector6d>& poses) {
  std::vector<std::vector<std::string>> rows;
  for (const Vector6d& v : poses) {
    const LegReadings legs = InverseKinematics(model.robot, model.robot.PoseFromVector(v));
    std::vector<std::string> row;
    for (int k = 0; k < 6; ++k) row.push_back(FormatNumber(v[k]));
    for (int i = 0; i < kNumLegs; ++i) row.push_back(FormatNumber(legs[i]));
    rows.push_back(row);
  }
  return WriteCsv(path, {"x", "y", "z", "q1", "q2", "q3", "L1", "L2", "L3", "L4", "L5", "L6"}, rows);
}

Status WriteHistoryCsv(const std::string& path, const PlanResult& plan) {
  std::vector<std::vector<std::string>> rows;
  for (const PlanIteration& step : plan.history) {
    rows.push_back({std::to_string(step.iteration), FormatNumber(step.indices.o1), FormatNumber(step.indices.o2),
                    FormatNumber(step.indices.o3), FormatNumber(step.indices.o4), FormatNumber(step.primary),
                    FormatNumber(step.secondary), step.exchanged ? "1" : "0"});
  }
  return WriteCsv(path, {"iteration", "O1", "O2", "O3", "O4", "primary", "secondary", "exchanged"}, rows);
}

namespace {

// What the plan buys, in the robot's unit: the lines under the indices.
std::string FormatPrediction(const PlanOutcome& outcome) {
  const PlanPrediction& p = outcome.prediction;
  const std::string unit = " " + outcome.length_unit;
  std::ostringstream out;
  out << std::setprecision(3);
  if (outcome.finite_primary) {
    out << "  " << (outcome.setup.planner.continuous ? "continuous search" : "continuous polish")
        << " from the finite plan: " << CriterionName(outcome.setup.planner.criterion) << " " << *outcome.finite_primary
        << " -> " << outcome.plan.final_primary;
    // S = 42 / Σσ: the reciprocal of the mean predicted parameter σ (core/sigma_criterion.h).
    if (outcome.setup.planner.criterion == Criterion::kS) {
      out << " (S = 1 / the mean predicted parameter sigma, in 1/" << outcome.length_unit << ")";
    }
    out << "\n";
  }
  if (!p.valid) return out.str() + "  predicted error: none (a leg's parameters are not identified)\n";
  if (const auto& sigma = outcome.reflector_sigma) {
    out << "  tracker: reflector σ " << sigma->first << " to " << sigma->second << unit << " over the plan's poses"
        << (outcome.line_of_sight ? ", every reflector in its line of sight" : "") << "\n"
        << "  predicted with each pose's covariance from the tracker, readings ±" << outcome.noise.leg << unit
        << " (calibrate's unweighted fit):\n";
  } else {
    out << "  predicted with noise ±" << outcome.noise.position << unit << ", ±" << outcome.noise.angle_deg
        << " deg, ±" << outcome.noise.leg << unit << " (calibrate's unweighted fit):\n";
  }
  out << "    parameter σ mean " << p.mean_sigma << unit << ", max " << p.max_sigma << unit
      << "; expected mean |error| " << p.mean_error << unit << "\n"
      << "    held-out FK error RMS " << p.heldout.position_rms << unit << ", " << p.heldout.orientation_rms_deg
      << " deg (parameters alone " << p.from_parameters.position_rms << unit << ", "
      << p.from_parameters.orientation_rms_deg << " deg)\n";
  return out.str();
}

}  // namespace

std::vector<std::string> UnreachablePoses(const Robot& robot, const std::vector<Vector6d>& poses) {
  // Where acquire starts (VisitOrder) and the sim machine stands: a LinuxCNC
  // machine's home is usually near it (the README's is 0.5 cm above).
  const Vector6d centre = MotionVectorFromPose(robot.PoseFromVector(WorkspaceCentre(robot)));
  std::vector<std::string> unreachable;
  for (size_t k = 0; k < poses.size(); ++k) {
    StatusOr<std::vector<Vector6d>> moves =
        PlanStraightMoves(robot, centre, MotionVectorFromPose(robot.PoseFromVector(poses[k])));
    if (!moves.ok()) unreachable.push_back("pose " + std::to_string(k + 1) + ": " + moves.status().message());
  }
  return unreachable;
}

nlohmann::json ToJson(const PlanOutcome& outcome) {
  const PlannerOptions& options = outcome.setup.planner;
  const PlanResult& plan = outcome.plan;
  nlohmann::json j = {{"initial", IndicesOnly(plan.initial)},
                      {"final", IndicesOnly(plan.final)},
                      {"iterations", plan.iterations},
                      {"best_iteration", plan.best_iteration},
                      {"converged", plan.converged},
                      {"seconds", plan.seconds},
                      {"poses", plan.poses.size()},
                      {"criterion", CriterionName(options.criterion)},
                      {"criterion_initial", plan.initial_primary},
                      {"criterion_final", plan.final_primary},
                      {"candidates", outcome.pool.poses.size()},
                      {"candidate_sources", outcome.pool.sources},
                      {"continuous", options.continuous},
                      {"out", outcome.out}};
  if (options.secondary) j["secondary"] = CriterionName(*options.secondary);
  j["polish"] = outcome.setup.polish;
  if (outcome.finite_primary) {
    j["finite_criterion"] = *outcome.finite_primary;
    j["finite_iterations"] = outcome.finite_iterations;
  }
  j["length_unit"] = outcome.length_unit;
  j["unreachable_from_centre"] = outcome.unreachable;
  j["predicted"] = ToJson(outcome.prediction, outcome.noise, /*weighted=*/false);
  if (const auto& sigma = outcome.reflector_sigma)
    j["tracker"] = {{"reflector_sigma_min", sigma->first},
                    {"reflector_sigma_max", sigma->second},
                    {"line_of_sight", outcome.line_of_sight}};
  if (const std::optional<PlanCertificate>& cert = outcome.certificate) {
    j["d_efficiency"] = cert->d_efficiency;
    j["gap"] = cert->design.gap;
    j["design_converged"] = cert->design.converged;
    j["design_support"] = cert->design.support;
    j["design_iterations"] = cert->design.iterations;
    j["s_efficiency"] = cert->s_efficiency;
    j["s_gap"] = cert->sigma_design.gap;
    j["s_design_converged"] = cert->sigma_design.converged;
    j["s_design_support"] = cert->sigma_design.support;
    j["best_mean_sigma"] = cert->BestMeanSigma(static_cast<int>(plan.poses.size()));
  }
  return j;
}

std::string FormatPlanSummary(const PlanOutcome& outcome) {
  const nlohmann::json s = ToJson(outcome);
  std::ostringstream out;
  auto line = [&](const char* label, const nlohmann::json& o) {
    out << "  " << std::left << std::setw(9) << label << std::right << std::fixed << std::setprecision(4) << "O1 "
        << std::setw(10) << o["O1"].get<double>() << "  O2 " << std::setw(8) << o["O2"].get<double>() << "  O3 "
        << std::setw(10) << o["O3"].get<double>() << "  O4 " << std::setw(8) << o["O4"].get<double>() << "\n";
  };
  out << "plan of " << s["poses"] << " poses from " << s["candidates"] << " candidates, criterion "
      << s["criterion"].get<std::string>();
  if (s.contains("secondary")) out << " / " << s["secondary"].get<std::string>();
  out << (s["continuous"].get<bool>() ? " (continuous)" : "") << "\n";
  line("initial", s["initial"]);
  line("final", s["final"]);
  const std::string unit = s["length_unit"].get<std::string>();
  out << "  (O1..O4: paper section 2, larger is better; O1, O3, O4 in " << unit
      << ", O2 a ratio; hexcal indices says what each measures)\n";
  out.unsetf(std::ios::floatfield);
  out << "  " << s["iterations"] << " iterations (best at " << s["best_iteration"] << ")"
      << (s["converged"].get<bool>() ? ", converged" : "") << ", " << std::setprecision(3) << s["seconds"].get<double>()
      << " s\n";
  if (s.contains("d_efficiency")) {
    out << "  D-efficiency >= " << std::setprecision(4) << s["d_efficiency"].get<double>() << " (design bound gap "
        << s["gap"].get<double>() << ")\n";
    out << "  S-efficiency >= " << s["s_efficiency"].get<double>() << " (design bound gap " << s["s_gap"].get<double>()
        << ")\n";
  }
  out << FormatPrediction(outcome);
  if (outcome.unreachable.empty())
    out << "  moves: every pose reachable from the centre of the sampling box by straight moves within the strokes\n";
  for (const std::string& why : outcome.unreachable) out << "  not reachable by straight moves: " << why << "\n";
  if (!outcome.out.empty()) out << "written to " << outcome.out << "\n";
  return out.str();
}

namespace {

bool UsesS(const PlannerOptions& options) {
  return options.criterion == Criterion::kS || options.secondary == Criterion::kS;
}

// The continuous phase's history after the finite one's: numbered on, its
// iteration 0 (the finite plan again) left out.
void AppendPhase(PlanResult second, PlanResult* first) {
  const int offset = first->iterations;
  for (size_t k = 1; k < second.history.size(); ++k) {
    second.history[k].iteration += offset;
    first->history.push_back(second.history[k]);
  }
  if (second.best_iteration > 0) first->best_iteration = offset + second.best_iteration;
  first->poses = std::move(second.poses);
  first->candidate_indices = std::move(second.candidate_indices);
  first->final = second.final;
  first->final_primary = second.final_primary;
  first->iterations = offset + second.iterations;
  first->converged = second.converged;
  first->seconds += second.seconds;
}

// Continuous IOOPS from the finite plan: `iterations` with the planner's
// options (its budget when 0), starts drawn from the pool.
Status ContinuousPhase(const PlanningModel& model, const PlanSetup& setup, int iterations, const JobHooks& hooks,
                       const PlanIterationObserver& on_iteration, PlanOutcome* outcome) {
  PlannerOptions options = setup.planner;
  options.continuous = true;
  options.iterations = iterations;
  const int offset = outcome->plan.iterations;
  PlanIterationObserver observer;
  if (on_iteration) {
    observer = [&](const PlanIteration& step) {
      if (step.iteration == 0) return;
      PlanIteration numbered = step;
      numbered.iteration += offset;
      on_iteration(numbered);
    };
  }
  StatusOr<PlanResult> second = PlanPoses(model, outcome->pool.poses, outcome->plan.poses, options, hooks, observer);
  if (!second.ok()) return second.status().AsFailure();
  outcome->finite_primary = outcome->plan.final_primary;
  outcome->finite_iterations = outcome->plan.iterations;
  AppendPhase(std::move(*second), &outcome->plan);
  return Status::Ok();
}

// The smallest and largest σ of a reflector over the poses.
std::pair<double, double> ReflectorSigmaRange(const TrackerModel& tracker, const Robot& robot,
                                              const std::vector<Vector6d>& poses) {
  std::pair<double, double> range(std::numeric_limits<double>::infinity(), 0);
  for (const Vector6d& v : poses)
    for (double sigma : ReflectorSigmas(tracker, robot.PoseFromVector(v)))
      range = {std::min(range.first, sigma), std::max(range.second, sigma)};
  return range;
}

// The certificates on the pool plus the plan's own poses (a polished pose is
// not in the pool), so that no efficiency can exceed 1.
Status Certify(const PlanningModel& model, const PlanSetup& setup, const CandidateRows& pool_rows,
               const JobHooks& hooks, PlanOutcome* outcome) {
  hooks.Stage("certificate");
  OptimalDesignOptions design_options;
  design_options.max_seconds = setup.certificate_seconds;
  std::vector<Vector6d> candidates = outcome->pool.poses;
  candidates.insert(candidates.end(), outcome->plan.poses.begin(), outcome->plan.poses.end());
  StatusOr<PlanCertificate> cert = CertifyPlan(model, candidates, outcome->plan.poses, design_options, &pool_rows);
  if (!cert.ok()) return cert.status().AsFailure();
  outcome->certificate = *cert;
  return Status::Ok();
}

}  // namespace

StatusOr<PlanOutcome> RunPlan(const PlanningModel& given_model, const PlanSetup& setup,
                              const std::string& candidates_file, const JobHooks& hooks,
                              const PlanIterationObserver& on_iteration) {
  if (Status s = setup.Check(); !s.ok()) return s;
  PlanningModel model = given_model;
  if (!model.noise && UsesS(setup.planner)) model.noise = NoiseModel{};  // S is a σ: it needs a noise model
  PlannerOptions finite = setup.planner;
  finite.continuous = false;
  if (setup.planner.continuous) finite.iterations = 0;  // the user's budget is the continuous phase's
  // Core's statuses carry the kind: a file the user named that is wrong, or a
  // robot without a pose box, is bad input; a generated set that cannot be had
  // (a box too tight) is a failed computation.
  StatusOr<std::vector<Vector6d>> initial = InitialPoses(model, setup.init, finite.num_poses, finite.seed);
  if (!initial.ok()) return initial.status();
  hooks.Stage("candidates");
  StatusOr<CandidatePool> pool =
      BuildCandidatePool(model, candidates_file, setup.candidate_kinds, setup.candidate_count, setup.planner.continuous,
                         finite.seed, hooks);
  if (!pool.ok()) return pool.status();
  hooks.Stage("planning");
  // The pool's rows once, for the search and the certificates.
  const CandidateRows pool_rows = model.RowsOf(pool->poses, finite.threads);
  StatusOr<PlanResult> plan = PlanPoses(model, pool->poses, &pool_rows, *initial, finite, hooks, on_iteration);
  if (!plan.ok()) return plan.status().AsFailure();
  PlanOutcome outcome{setup, std::move(*pool), std::move(*plan), std::nullopt, "", std::nullopt, 0, {}, {}};
  const int continuous_iterations = setup.planner.continuous ? setup.planner.IterationBudget() : setup.polish;
  if (continuous_iterations > 0) {
    hooks.Stage(setup.planner.continuous ? "continuous" : "polishing");
    if (Status s = ContinuousPhase(model, setup, continuous_iterations, hooks, on_iteration, &outcome); !s.ok()) {
      return s;
    }
  }
  if (setup.certificate) {
    if (Status s = Certify(model, setup, pool_rows, hooks, &outcome); !s.ok()) return s;
  }
  hooks.Stage("prediction");
  outcome.length_unit = LengthUnitName(model.robot.length_unit);
  outcome.noise = model.noise.value_or(NoiseModel{});
  if (model.tracker) {
    outcome.prediction = PredictPlanError(model, outcome.plan.poses, outcome.noise, /*weighted=*/false,
                                          ValidationPoses(model.robot));
    outcome.reflector_sigma = ReflectorSigmaRange(*model.tracker, model.robot, outcome.plan.poses);
    outcome.line_of_sight = model.tracker->settings.position.has_value();
  } else {
    outcome.prediction = PredictPlanError(model.robot, outcome.plan.poses, outcome.noise, /*weighted=*/false,
                                          ValidationPoses(model.robot));
  }
  outcome.unreachable = UnreachablePoses(model.robot, outcome.plan.poses);
  return outcome;
}

namespace {

StatusOr<PlanningModel> ModelOfRobot(const std::string& name) {
  StatusOr<Robot> robot = LoadRobot(name);
  if (!robot.ok()) return robot.status();
  return PlanningModel{*robot, std::nullopt, std::nullopt};
}

// Robot or session, settings file and entries: the model and the setup of a request.
StatusOr<std::pair<PlanningModel, PlanSetup>> ResolvePlanRequest(const PlanRequest& request) {
  if (request.robot.empty() == request.session.empty())
    return Status::BadInput("give the robot (--robot) or a session (--session), one of them");
  const bool session = !request.session.empty();
  StatusOr<PlanningModel> loaded = session ? SessionPlanningModel(request.session) : ModelOfRobot(request.robot);
  if (!loaded.ok()) return loaded.status();
  PlanningModel model = std::move(*loaded);
  PlanSetup setup;
  if (!request.settings.empty()) {
    StatusOr<PlanSettings> settings = LoadPlanSettings(request.settings, model.robot);
    if (!settings.ok()) return settings.status();
    // A session's noise model stays unless the file gives one.
    if (settings->noise || !session) model.noise = settings->noise;
    model.measurement = settings->measurement;
    const std::string section = "plan settings '" + request.settings + "': planner";
    if (Status s = ApplyOptionEntries(PlanSetupOptions(), settings->planner, &setup, section); !s.ok()) return s;
  }
  if (Status s = ApplyOptionEntries(PlanSetupOptions(), request.planner_entries, &setup, "plan"); !s.ok()) return s;
  if (!request.noise_entries.empty()) {
    NoiseModel noise = model.noise.value_or(NoiseModel{});
    if (Status s = ApplyOptionEntries(NoiseModelOptions(), request.noise_entries, &noise, "noise"); !s.ok()) return s;
    model.noise = noise;
  }
  return std::make_pair(model, setup);
}

}  // namespace

StatusOr<PlanOutcome> PlanFromRequest(const PlanRequest& request, const JobHooks& hooks) {
  StatusOr<std::pair<PlanningModel, PlanSetup>> resolved = ResolvePlanRequest(request);
  if (!resolved.ok()) return resolved.status();
  const auto& [model, setup] = *resolved;
  StatusOr<PlanOutcome> outcome = RunPlan(model, setup, request.candidates_file, hooks);
  if (!outcome.ok()) return outcome.status();
  if (!request.out.empty()) {
    if (Status s = WritePlanCsv(request.out, model, outcome->plan.poses); !s.ok()) return s;
    outcome->out = request.out;
  }
  if (!request.history.empty()) {
    if (Status s = WriteHistoryCsv(request.history, outcome->plan); !s.ok()) return s;
  }
  return outcome;
}

}  // namespace hexcal::workflow
