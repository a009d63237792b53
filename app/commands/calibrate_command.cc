// hexcal calibrate --robot R --measurements M.csv --out calibrated.yaml [--force]
//   [--loss none|huber|cauchy] [--loss-scale s]
//   [--weighted [--noise-position p] [--noise-angle a] [--noise-leg l]] [--json]
// hexcal calibrate --session DIR [--two-stage | --from-pixels | --from-points] [--estimate focal,principal,scale|none]
//   [--keep-reflectors] [--keep-outliers] [--outlier-threshold Z] [--json]
//   (workflow/session_calibrate.h)
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "app/commands/option_flags.h"
#include "core/calibration.h"
#include "core/calibration_file.h"
#include "core/robot_io.h"
#include "report/calibration_verdict.h"
#include "workflow/session_calibrate.h"

namespace hexcal::cli {
namespace {

struct CalibrateCliOptions {
  std::string robot, measurements, out, session;
  std::string estimate = OptionText(workflow::PixelEstimatesOption(), workflow::FromPixelsRequest{});
  bool from_pixels = false, from_points = false, two_stage = false, keep_reflectors = false;
  bool force = false, json = false, wait = false;
  std::shared_ptr<OptionEntries> calibration = std::make_shared<OptionEntries>();  // --loss, --loss-scale, --weighted
  std::shared_ptr<OptionEntries> noise = std::make_shared<OptionEntries>();  // --noise-* over the defaults
  std::shared_ptr<OptionEntries> outliers = std::make_shared<OptionEntries>();  // --keep-outliers, --outlier-threshold
  OptionFlagNames flags;
};

int RunCalibrateSession(const CalibrateCliOptions& cli, std::ostream& out, std::ostream& err) {
  workflow::CalibrateSessionRequest request;
  request.session = cli.session;
  request.wait = cli.wait ? LockWait::kForever : LockWait::kNo;
  if (Status s = ApplyOptionEntries(OutlierScreeningOptions(), *cli.outliers, &request.outliers, "outliers"); !s.ok())
    return ReportError(err, "calibrate", s);
  StatusOr<workflow::FromPixelsRequest> estimates = workflow::ParsePixelEstimates(cli.estimate);
  if (!estimates.ok()) return ReportError(err, "calibrate", estimates.status());
  request.from_pixels = *estimates;
  request.from_pixels.enabled = !cli.two_stage;
  request.from_pixels.fall_back = !cli.from_pixels;
  request.from_points.enabled = !cli.two_stage;
  request.from_points.fall_back = !cli.from_points;
  request.from_points.estimate_reflectors = !cli.keep_reflectors;
  TerminalJob job("", &err);  // notes ("measuring 32 images: the camera changed ...") on stderr
  StatusOr<workflow::CalibrationReport> report = workflow::CalibrateSession(request, job.hooks());
  if (!report.ok()) return ReportError(err, "calibrate", report.status(), cli.flags);
  const workflow::Verdict verdict = workflow::MakeVerdict(*report);
  if (cli.json) {
    nlohmann::json json = workflow::ToJson(*report);
    json["verdict"] = verdict.ToJson();
    out << JsonText(json);
  } else {
    out << workflow::FormatCalibrationSummary(*report) << verdict.ToText();
  }
  return kExitOk;
}

std::string DirectionText(const LegParameters& direction) {
  std::string text;
  for (int k = 0; k < kParamsPerLeg; ++k) {
    if (std::abs(direction[k]) < 0.05) continue;
    char term[48];
    std::snprintf(term, sizeof term, "%s%.2f %s", text.empty() ? "" : " ", direction[k], ParameterName(k));
    text += term;
  }
  return text;
}

nlohmann::json NamedParameters(const LegParameters& values) {
  nlohmann::json j;
  for (int k = 0; k < kParamsPerLeg; ++k) j[ParameterName(k)] = values[k];
  return j;
}

nlohmann::json LegJson(const LegCalibration& leg) {
  nlohmann::json weak = nlohmann::json::array(), correlated = nlohmann::json::array();
  for (const WeakDirection& w : leg.unidentifiable) {
    weak.push_back({{"ratio", w.ratio}, {"direction", NamedParameters(w.direction)}});
  }
  for (const CorrelatedPair& c : leg.correlated) {
    correlated.push_back(
        {{"first", ParameterName(c.first)}, {"second", ParameterName(c.second)}, {"correlation", c.correlation}});
  }
  return {{"nominal", NamedParameters(leg.initial)},
          {"estimate", NamedParameters(leg.estimate)},
          {"sigma", leg.has_uncertainty ? NamedParameters(leg.std_dev) : nlohmann::json(nullptr)},
          {"variance_factor", leg.has_uncertainty ? nlohmann::json(leg.variance_factor) : nlohmann::json(nullptr)},
          {"residual_rms", leg.residual_rms},
          {"iterations", leg.iterations},
          {"termination", leg.termination},
          {"singular_values", std::vector<double>(leg.singular_values.data(), leg.singular_values.data() + 7)},
          {"unidentifiable", weak},
          {"correlated", correlated}};
}

void PrintReport(const CalibrateCliOptions& cli, const CalibrationResult& result, std::ostream& out) {
  const char* unit = LengthUnitName(result.robot.length_unit);
  out << "calibrated robot " << result.robot.name << " from " << result.num_measurements << " measurements ("
      << cli.measurements << ") -> " << cli.out << "\n"
      << "lengths in " << unit << "; sigma = one standard deviation; identified = |change|/sigma (well above 3: the "
      << "parameter was identified and differs from nominal, not an alarm)\n\n"
      << "leg param      nominal   calibrated  change (" << unit << ")   sigma (" << unit << ")  identified\n";
  char line[160];
  for (int i = 0; i < kNumLegs; ++i) {
    const LegCalibration& leg = result.legs[i];
    for (int k = 0; k < kParamsPerLeg; ++k) {
      std::snprintf(line, sizeof line, "%3d %-5s %12.5f %12.5f %12.5f ", i + 1, ParameterName(k), leg.initial[k],
                    leg.estimate[k], leg.estimate[k] - leg.initial[k]);
      out << line;
      if (leg.has_uncertainty) {
        const double change = std::abs(leg.estimate[k] - leg.initial[k]);
        std::snprintf(line, sizeof line, "%12.3g %11.3g\n", leg.std_dev[k],
                      leg.std_dev[k] > 0 ? change / leg.std_dev[k] : 0.0);
        out << line;
      } else {
        out << "           -\n";
      }
    }
  }
  out << "\nleg  residual RMS  iterations  termination   sigma_min/sigma_max\n";
  for (int i = 0; i < kNumLegs; ++i) {
    const LegCalibration& leg = result.legs[i];
    std::snprintf(line, sizeof line, "%3d  %12.3g  %10d  %-12s  %10.3g\n", i + 1, leg.residual_rms, leg.iterations,
                  leg.termination.c_str(), leg.singular_values[6] / leg.singular_values[0]);
    out << line;
  }
  if (result.num_measurements == kParamsPerLeg) {
    out << "note: 7 measurements fit each leg exactly; no uncertainty can be estimated (measure more poses)\n";
  }
  bool any = false;
  for (int i = 0; i < kNumLegs; ++i) {
    const LegCalibration& leg = result.legs[i];
    for (const WeakDirection& w : leg.unidentifiable) {
      out << (any ? "" : "\nidentifiability warnings:\n") << "  leg " << i + 1
          << ": barely identifiable direction (sigma ratio " << w.ratio << "): " << DirectionText(w.direction) << "\n";
      any = true;
    }
    for (const CorrelatedPair& c : leg.correlated) {
      out << (any ? "" : "\nidentifiability warnings:\n") << "  leg " << i + 1 << ": " << ParameterName(c.first)
          << " and " << ParameterName(c.second) << " are strongly correlated (" << c.correlation << ")\n";
      any = true;
    }
  }
}

int RunCalibrate(const CalibrateCliOptions& cli, std::ostream& out, std::ostream& err) {
  StatusOr<Robot> robot = LoadRobot(cli.robot);
  if (!robot.ok()) return ReportError(err, "calibrate", robot.status());
  StatusOr<std::vector<Measurement>> measurements = LoadMeasurements(cli.measurements);
  if (!measurements.ok()) return ReportError(err, "calibrate", measurements.status());
  CalibrationOptions options;
  if (Status s = ApplyOptionEntries(CalibrationOptionSpecs(), *cli.calibration, &options, "calibrate"); !s.ok())
    return ReportError(err, "calibrate", s);
  if (Status s = ApplyOptionEntries(NoiseModelOptions(), *cli.noise, &options.noise, "noise"); !s.ok())
    return ReportError(err, "calibrate", s);
  // Past valid options, what CheckCalibrationInput and Calibrate reject is the
  // measurement file's content: name the file.
  std::string options_error;
  if (!options.IsValid(&options_error)) return ReportError(err, "calibrate", Status::BadInput(options_error));
  const auto in_file = [&](const Status& s) { return Status::BadInput(cli.measurements + ": " + s.message()); };
  if (Status s = CheckCalibrationInput(*robot, *measurements, options); !s.ok()) {
    return ReportError(err, "calibrate", in_file(s));
  }
  if (Status s = CheckOutputFree(cli.out, cli.force); !s.ok()) return ReportError(err, "calibrate", s);

  ProgressBar progress("calibrate (legs)");
  StatusOr<CalibrationResult> result =
      Calibrate(*robot, *measurements, options, {[&](int done, int total) { progress.Update(done, total); }});
  if (!result.ok()) return ReportError(err, "calibrate", (in_file(result.status())).AsFailure());
  const CalibrationInputs inputs{cli.robot, cli.measurements, options, CurrentUtcTimestamp()};
  if (Status s = SaveCalibratedRobot(cli.out, *result, inputs); !s.ok()) {
    return ReportError(err, "calibrate", s);
  }

  if (cli.json) {
    nlohmann::json legs = nlohmann::json::array();
    for (const LegCalibration& leg : result->legs) legs.push_back(LegJson(leg));
    out << JsonText(nlohmann::json{{"out", cli.out},
                                   {"measurements", result->num_measurements},
                                   {"length_unit", LengthUnitName(result->robot.length_unit)},
                                   {"robot", RobotJson(result->robot)},
                                   {"legs", legs}});
  } else {
    PrintReport(cli, *result, out);
  }
  return kExitOk;
}

}  // namespace

void AddCalibrateCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<CalibrateCliOptions>();
  CLI::App* sub = app.add_subcommand("calibrate", "identify the 42 kinematic parameters from measurements");
  CLI::Option* session =
      sub->add_option("--session", options->session, "session folder: measure, register, calibrate, validate");
  sub->add_option("--robot", options->robot, "nominal robot file or preset name (the starting point)")
      ->excludes(session);
  sub->add_option("--measurements", options->measurements, "measurements CSV: x,y,z,q1,q2,q3,L1..L6")
      ->excludes(session);
  sub->add_option("--out", options->out, "calibrated robot file to write")->excludes(session);
  sub->add_flag("--force", options->force, "overwrite --out if it exists");
  // A session calibrates weighted by the session's noise model (docs/session.md):
  // these options belong to the --measurements mode only.
  for (const OptionSpec<CalibrationOptions>& spec : CalibrationOptionSpecs())
    AddOneOptionFlag(sub, spec, options->calibration, &options->flags)->excludes(session);
  CLI::Option* weighted = sub->get_option("--weighted");
  for (const OptionSpec<NoiseModel>& spec : NoiseModelOptions())
    AddOneOptionFlag(sub, spec, options->noise, &options->flags, "noise-")->needs(weighted);
  // Outlier screening of the session's readings (docs/calibration.md, "Outliers").
  for (const OptionSpec<OutlierScreening>& spec : OutlierScreeningOptions())
    AddOneOptionFlag(sub, spec, options->outliers, &options->flags)->needs(session);
  // The calibration from pixels is the default (docs/calibration.md).
  CLI::Option* from_pixels =
      sub->add_flag("--from-pixels", options->from_pixels,
                    "fit the parameters to the tag corners (the default) and fail if that fails, instead of keeping "
                    "the two-stage calibration")
          ->needs(session);
  // A points session's counterpart: the calibration from points, its default.
  CLI::Option* from_points =
      sub->add_flag("--from-points", options->from_points,
                    "a points session: fit the parameters and the reflectors to the measured points (the default) and "
                    "fail if that fails, instead of keeping the two-stage calibration")
          ->needs(session)
          ->excludes(from_pixels);
  CLI::Option* two_stage =
      sub->add_flag("--two-stage", options->two_stage,
                    "only fit the legs to the measured poses (no calibration from pixels or from points)")
          ->needs(session)
          ->excludes(from_pixels)
          ->excludes(from_points);
  sub->add_flag("--keep-reflectors", options->keep_reflectors,
                "a points session: keep the reflectors as given (or as estimated from the poses) in the calibration "
                "from points instead of estimating them")
      ->needs(session)
      ->excludes(two_stage);
  sub->add_option(workflow::PixelEstimatesOption().Flag(), options->estimate, workflow::PixelEstimatesOption().help)
      ->capture_default_str()
      ->needs(session)
      ->excludes(two_stage);
  sub->add_flag("--json", options->json, "print one JSON object on stdout");
  sub->add_flag("--wait", options->wait,
                "when another program writes the session, wait for it instead of stopping (exit 3)")
      ->needs(session);
  sub->callback([=] {
    if (!options->session.empty()) {
      *exit_code = RunCalibrateSession(*options, std::cout, std::cerr);
    } else if (options->robot.empty() || options->measurements.empty() || options->out.empty()) {
      *exit_code =
          ReportError(std::cerr, "calibrate", Status::BadInput("give --robot, --measurements and --out, or --session"));
    } else {
      *exit_code = RunCalibrate(*options, std::cout, std::cerr);
    }
  });
}

}  // namespace hexcal::cli
