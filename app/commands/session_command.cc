// hexcal session init --robot R --camera C --target T DIR [--noise-position p]
// hexcal session init --robot R --instrument points --points FILE [--reflectors FILE] [--point-sigma S] DIR
//   [--tracker-position x,y,z] [--tracker-sigma-law linear --tracker-sigma0 s --tracker-sigma-per-distance k]
//   [--tracker-acceptance-deg a] [--tracker-leg-radius r]
//   [--noise-angle a] [--noise-leg l] [--json]
// hexcal session status DIR [--json]
// hexcal session check-noise DIR (--points FILE | --images FOLDER) [--wait] [--json]
// hexcal session record DIR --image NAME --legs L1,...,L6 [--from FILE] [--holdout] [--replace] [--wait] [--json]
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <vector>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "app/commands/option_flags.h"
#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/point_file.h"
#include "core/reading_units.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "core/tracker_model.h"
#include "workflow/noise_check.h"
#include "workflow/reading_check.h"
#include "workflow/session_edits.h"
#include "workflow/session_init.h"
#include "workflow/session_status.h"
#include "vision/camera.h"
#include "vision/target.h"

namespace hexcal::cli {
namespace {

struct SessionInitOptions {
  std::string dir;
  SessionConfig config;
  std::string instrument = "camera";
  double point_sigma_mm = 0.02;  // --point-sigma when not given: a laser tracker's, 0.02 mm
  bool point_sigma_given = false;
  bool json = false;
  std::shared_ptr<OptionEntries> noise = std::make_shared<OptionEntries>();  // --noise-*
  std::string tracker_position;                                              // "x,y,z"
  std::shared_ptr<OptionEntries> tracker = std::make_shared<OptionEntries>();  // --tracker-*
  OptionFlagNames flags;
};

// Points sessions: session.yaml's `tracker:` section from --tracker-position
// and the --tracker-* flags of TrackerSettingsOptions(), when any is given.
Status ApplyTrackerFlags(SessionInitOptions* cli) {
  if (cli->tracker_position.empty() && cli->tracker->empty()) return Status::Ok();
  if (cli->instrument != "points") return Status::BadInput("--tracker-* are for points sessions (--instrument points)");
  TrackerSettings tracker;
  if (!cli->tracker_position.empty()) {
    StatusOr<std::vector<double>> xyz = ParseNumberList(cli->tracker_position, 3, "--tracker-position");
    if (!xyz.ok()) return xyz.status();
    tracker.position = Eigen::Vector3d((*xyz)[0], (*xyz)[1], (*xyz)[2]);
  }
  if (Status s = ApplyOptionEntries(TrackerSettingsOptions(), *cli->tracker, &tracker, "tracker"); !s.ok()) return s;
  cli->config.tracker = tracker;
  return Status::Ok();
}

// A file the user named from here, as session.yaml keeps it: relative to the
// session folder (workflow/session_init.h, which the GUI's New session uses too).
using workflow::AsSessionPath;

// With a reflector file and no --noise-position or --noise-angle: the pose
// noise the tracker's σ implies for these reflectors (√3 σ as the uniform
// half-width, core/noise_model.h), which `hexcal plan` and the GUI's plan
// weigh by; the calibration replaces it by the measured fits' own.
Status PoseNoiseFromReflectors(const std::vector<NamedPoint>& reflectors, SessionInitOptions* cli) {
  SessionConfig& config = cli->config;
  for (const auto& [key, value] : *cli->noise)
    if (key == "position" || key == "angle_deg" || key == "angle") return Status::Ok();
  StatusOr<std::pair<double, double>> sigma = PoseSigmaOfReflectors(reflectors, config.point_sigma);
  if (!sigma.ok()) return Status::BadInput(config.reflectors + ": " + sigma.status().message());
  config.noise.position = std::sqrt(3.0) * sigma->first;
  config.noise.angle_deg = std::sqrt(3.0) * sigma->second;
  return Status::Ok();
}

// --instrument points: the points file (which the tracker may write later),
// the reflector file (checked now when given) and the σ, robot unit.
Status PreparePointSession(const Robot& robot, SessionInitOptions* cli) {
  SessionConfig& config = cli->config;
  if (!config.camera.empty() || !config.target.empty())
    return Status::BadInput("--camera and --target are for camera sessions; a points session has --points");
  if (config.points.empty()) return Status::BadInput("--instrument points needs --points FILE (the tracker's export)");
  config.instrument = Instrument::kPoints;
  if (!cli->point_sigma_given) config.point_sigma = cli->point_sigma_mm * 0.001 / MetresPerUnit(robot.length_unit);
  if (!config.reflectors.empty()) {  // read once: checked now, and the pose noise it implies
    StatusOr<std::vector<NamedPoint>> reflectors = LoadReflectorFile(config.reflectors);
    if (!reflectors.ok()) return reflectors.status();
    if (Status s = PoseNoiseFromReflectors(*reflectors, cli); !s.ok()) return s;
  }
  for (std::string* name : {&config.robot, &config.points, &config.reflectors})
    if (!name->empty()) *name = AsSessionPath(cli->dir, *name);
  return Status::Ok();
}

Status PrepareCameraSession(SessionInitOptions* cli) {
  SessionConfig& config = cli->config;
  if (config.camera.empty() || config.target.empty())
    return Status::BadInput("a camera session needs --camera and --target (or --instrument points)");
  if (StatusOr<Camera> camera = LoadCamera(config.camera); !camera.ok()) return camera.status();
  if (StatusOr<Target> target = LoadTarget(config.target); !target.ok()) return target.status();
  for (std::string* name : {&config.robot, &config.camera, &config.target}) *name = AsSessionPath(cli->dir, *name);
  return Status::Ok();
}

// Where a name session.yaml keeps (relative to the session) is from here.
std::string ResolvedInSession(const std::string& dir, const std::string& name) {
  const std::filesystem::path path(name);
  return path.is_absolute() ? name : (std::filesystem::path(dir) / path).lexically_normal().string();
}

int RunSessionInit(SessionInitOptions cli, std::ostream& out, std::ostream& err) {
  if (Status s = ApplyOptionEntries(NoiseModelOptions(), *cli.noise, &cli.config.noise, "noise"); !s.ok())
    return ReportError(err, "session init", s);
  if (Status s = ApplyTrackerFlags(&cli); !s.ok()) return ReportError(err, "session init", s);
  // Check that the names load now rather than at the first calibration.
  StatusOr<Robot> robot = LoadRobot(cli.config.robot);
  if (!robot.ok()) return ReportError(err, "session init", robot.status());
  const Status prepared =
      cli.instrument == "points" ? PreparePointSession(*robot, &cli) : PrepareCameraSession(&cli);
  if (!prepared.ok()) return ReportError(err, "session init", prepared);
  if (Status s = InitSession(cli.dir, cli.config); !s.ok()) return ReportError(err, "session init", s, cli.flags);
  const SessionPaths paths(cli.dir);
  if (cli.json) {
    out << JsonText({{"session", cli.dir}, {"config", paths.config}, {"images", paths.images}});
  } else if (cli.config.instrument == Instrument::kPoints) {
    out << "session " << cli.dir << ": wrote " << paths.config << "; put the measured points in "
        << ResolvedInSession(cli.dir, cli.config.points) << " and their readings in " << paths.legs
        << " (pose,L1..L6,holdout; pose as the points file names it)\n"
        << "noise: " << NoiseModelText(cli.config.noise)
        << (cli.config.reflectors.empty() ? "" : " (position and angle_deg from the reflectors and --point-sigma)");
    if (cli.config.reflectors.empty()) {
      out << "; plan with hexcal plan --noise-position " << FormatSignificant(cli.config.noise.position)
          << " --noise-angle " << FormatSignificant(cli.config.noise.angle_deg) << "\n";
    } else {  // the planner weighs each pose by the tracker's covariance there (docs/planner.md)
      out << "; plan with hexcal plan --session " << cli.dir << " --out " << paths.plan << "\n";
    }
  } else {
    out << "session " << cli.dir << ": wrote " << paths.config << "; put the images in " << paths.images
        << " and their readings in " << paths.legs << " (image,L1..L6,holdout)\n";
  }
  return kExitOk;
}

struct SessionRecordOptions {
  std::string dir, image, from, legs;  // legs: "L1,...,L6", read by ParseNumberList (decimal only)
  bool holdout = false, replace = false, wait = false, json = false;
};

// The image the row is for, when it is already in images/: a FIFO or a
// dangling link there gets its own message (core/atomic_file.h).
Status CheckImageInSession(const SessionPaths& paths, const std::string& image) {
  const std::filesystem::path path = std::filesystem::path(paths.images) / image;
  std::error_code error;
  if (!std::filesystem::exists(std::filesystem::symlink_status(path, error)))
    return Status::BadInput(paths.images + "/" + Excerpt(image) +
                            ": no such image; put it there first, or give --from");
  return CheckFileForReading(path.string(), kMaxImageBytes);
}

// Readings as typed on the command line (issue 36: 1e300 and -1000 were
// recorded "done"): each within a stroke length of its leg's stroke in the
// session's robot file, the bound calibrate --measurements applies
// (core/reading_units.h). Not the stroke itself: a real robot's readings, the
// demo's too, fall a little outside the nominal file's strokes. Bad input
// naming the reading, its value and the range; readings in another length
// unit are named as such.
Status CheckTypedLegs(const std::string& dir, const std::vector<double>& legs) {
  StatusOr<workflow::ReadingCheck> check = workflow::SessionReadingCheck(dir);
  if (!check.ok()) return check.status();
  const Robot& robot = check->robot;
  LegReadings readings;
  for (int i = 0; i < kNumLegs; ++i) readings[i] = legs[static_cast<size_t>(i)];
  if (Status s = CheckReadingsUnit(robot, {readings}, ""); !s.ok()) return Status::BadInput("--legs: " + s.message());
  const std::string unit = " " + std::string(LengthUnitName(robot.length_unit));
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg& leg = robot.legs[i];
    const double slack = kFarOutsideStrokes * (leg.stroke_max - leg.stroke_min);
    if (readings[i] >= leg.stroke_min - slack && readings[i] <= leg.stroke_max + slack) continue;
    return Status::BadInput("--legs: L" + std::to_string(i + 1) + " = " + FormatNumber(readings[i]) + unit +
                            " is outside [" + FormatNumber(leg.stroke_min - slack) + ", " +
                            FormatNumber(leg.stroke_max + slack) + "]" + unit + ", leg " + std::to_string(i + 1) +
                            "'s stroke [" + FormatNumber(leg.stroke_min) + ", " + FormatNumber(leg.stroke_max) + "]" +
                            unit + " give or take a stroke length; not saved (a typo?)");
  }
  return Status::Ok();
}

// One row of legs.csv, written under the session lock into legs.csv as it is
// on disk (workflow/session_edits.h): rows others wrote are kept.
int RunSessionRecord(const SessionRecordOptions& cli, std::ostream& out, std::ostream& err) {
  const SessionPaths paths(cli.dir);
  StatusOr<std::vector<double>> legs = ParseNumberList(cli.legs, kNumLegs, "--legs");
  if (!legs.ok()) return ReportError(err, "session record", legs.status());
  // Images only: a points session's legs.csv is keyed by pose, and an image
  // row written into it would break it.
  StatusOr<SessionConfig> config = LoadSessionConfig(cli.dir);
  if (!config.ok()) return ReportError(err, "session record", config.status());
  if (config->instrument == Instrument::kPoints)
    return ReportError(err, "session record",
                       Status::BadInput(cli.dir + " is a points session: its legs.csv rows are poses " +
                                        "(pose,L1..L6,holdout), not images; write them there or in the GUI's readings "
                                        "table (Measure step)"));
  if (Status s = CheckTypedLegs(cli.dir, *legs); !s.ok()) return ReportError(err, "session record", s);
  if (cli.from.empty())
    if (Status s = CheckImageInSession(paths, cli.image); !s.ok()) return ReportError(err, "session record", s);
  LegsRow row;
  row.image = cli.image;
  for (int i = 0; i < kNumLegs; ++i) row.legs[i] = (*legs)[static_cast<size_t>(i)];
  row.holdout = cli.holdout;
  const workflow::EditOptions options{cli.replace, cli.wait ? LockWait::kForever : LockWait::kNo};
  const workflow::EditOutcome done = cli.from.empty()
                                         ? workflow::ApplyLegsEdit(cli.dir, workflow::LegsEdit::SetRow(row), options)
                                         : workflow::RecordCapture(cli.dir, cli.from, row, options);
  if (!done.status.ok()) return ReportError(err, "session record", done.status);
  if (done.conflict)
    return ReportError(err, "session record", Status::BadInput(done.conflict_text + "; use --replace to replace it"));
  if (cli.json)
    out << JsonText({{"session", cli.dir}, {"image", cli.image}, {"legs", paths.legs}, {"holdout", cli.holdout}});
  else
    out << "session " << cli.dir << ": " << cli.image << " recorded in " << paths.legs << "\n";
  return kExitOk;
}

void AddSessionRecord(CLI::App* session, int* exit_code) {
  auto options = std::make_shared<SessionRecordOptions>();
  CLI::App* record = session->add_subcommand("record", "write the leg readings of one image into DIR/legs.csv");
  record->add_option("dir", options->dir, "session folder")->required()->check(CLI::ExistingDirectory);
  record->add_option("--image", options->image, "image file name in DIR/images/")->required();
  record->add_option("--legs", options->legs, "the six readings L1,...,L6, robot unit")->required();
  record->add_option("--from", options->from,
                     "copy this image file into DIR/images/ as --image, with its row, in one locked step");
  record->add_flag("--holdout", options->holdout, "keep the image out of the calibration, to validate it");
  record->add_flag("--replace", options->replace, "replace the image's readings if legs.csv has them already");
  record->add_flag("--wait", options->wait, "when another program writes the session, wait for it (else exit 3)");
  record->add_flag("--json", options->json, "print one JSON object on stdout");
  record->callback([=] { *exit_code = RunSessionRecord(*options, std::cout, std::cerr); });
}

void AddSessionStatus(CLI::App* session, int* exit_code) {
  auto dir = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  CLI::App* status = session->add_subcommand("status", "where each step of DIR stands, from the files' contents");
  status->add_option("dir", *dir, "session folder")->required();
  status->add_flag("--json", *json, "print one JSON object on stdout");
  status->callback([=] {
    StatusOr<workflow::SessionStatus> read = workflow::ReadSessionStatus(*dir);
    if (!read.ok()) {
      *exit_code = ReportError(std::cerr, "session status", read.status());
      return;
    }
    std::cout << (*json ? JsonText(workflow::ToJson(*read)) : workflow::FormatSessionStatus(*read));
    *exit_code = kExitOk;
  });
}

struct CheckNoiseOptions {
  std::string dir, points, images;
  bool wait = false, json = false;
};

// One pose measured k times against the session's declared noise (workflow/noise_check.h).
int RunCheckNoise(const CheckNoiseOptions& cli, std::ostream& out, std::ostream& err) {
  StatusOr<SessionConfig> config = LoadSessionConfig(cli.dir);
  if (!config.ok()) return ReportError(err, "session check-noise", config.status());
  const bool points = config->instrument == Instrument::kPoints;
  const std::string& input = points ? cli.points : cli.images;
  if (input.empty() || !(points ? cli.images : cli.points).empty())
    return ReportError(
        err, "session check-noise",
        Status::BadInput(points ? "a points session's repeatability takes --points FILE (k point sets of "
                                  "one pose)"
                                : "a camera session's repeatability takes --images FOLDER (k images of "
                                  "one pose)"));
  TerminalJob job("", cli.json ? &err : &out);
  StatusOr<workflow::NoiseCheck> check = workflow::CheckSessionNoise(
      {cli.dir, input, cli.wait ? LockWait::kForever : LockWait::kNo}, job.hooks());
  if (!check.ok()) return ReportError(err, "session check-noise", check.status());
  out << (cli.json ? JsonText(workflow::ToJson(*check)) : workflow::FormatNoiseCheck(*check));
  return kExitOk;
}

void AddSessionCheckNoise(CLI::App* session, int* exit_code) {
  auto options = std::make_shared<CheckNoiseOptions>();
  CLI::App* check = session->add_subcommand(
      "check-noise", "measure one pose k times and compare the scatter with the session's declared noise");
  check->add_option("dir", options->dir, "session folder")->required()->check(CLI::ExistingDirectory);
  check->add_option("--points", options->points, "points sessions: k point sets of one pose (either points layout)");
  check->add_option("--images", options->images, "camera sessions: a folder of k images of one pose");
  check->add_flag("--wait", options->wait, "when another program writes the session, wait for it (else exit 3)");
  check->add_flag("--json", options->json, "print one JSON object on stdout");
  check->callback([=] { *exit_code = RunCheckNoise(*options, std::cout, std::cerr); });
}

}  // namespace

void AddSessionCommand(CLI::App& app, int* exit_code) {
  CLI::App* session =
      app.add_subcommand("session", "create a session folder, record readings, show its status (docs/session.md)");
  session->require_subcommand(1);
  auto options = std::make_shared<SessionInitOptions>();
  CLI::App* init = session->add_subcommand("init", "create DIR with session.yaml, images/ and results/");
  init->add_option("dir", options->dir, "session folder")->required();
  init->add_option("--robot", options->config.robot, "nominal robot file or preset name")->required();
  init->add_option("--instrument", options->instrument,
                   "what measures the platform's pose: camera (images of an AprilTag board) or points (named 3D "
                   "points, a laser tracker's or CMM's; docs/calibration.md, Point measurements)")
      ->check(CLI::IsMember({"camera", "points"}))
      ->capture_default_str();
  init->add_option("--camera", options->config.camera, "camera sessions: camera file (hexcal intrinsics)");
  init->add_option("--target", options->config.target, "camera sessions: target file or name");
  init->add_option("--points", options->config.points,
                   "points sessions: the points file, CSV pose,point,x,y,z[,sigma] or SpatialAnalyzer ASCII, robot "
                   "unit (it may be written later)");
  init->add_option("--reflectors", options->config.reflectors,
                   "points sessions: the reflectors' positions on the platform, CSV point,x,y,z (default: estimated "
                   "from the measured poses)");
  init->add_option("--point-sigma", options->config.point_sigma,
                   "points sessions: sigma of each coordinate where the points file gives none, robot unit "
                   "(default: 0.02 mm in the robot's unit)")
      ->check(CLI::PositiveNumber)
      ->each([options](const std::string&) { options->point_sigma_given = true; });
  AddOptionFlags(init, NoiseModelOptions(), options->noise, &options->flags, "noise-");
  init->add_option("--tracker-position", options->tracker_position,
                   "points sessions: the tracker's head in the base frame, x,y,z in the robot's unit: the planner "
                   "keeps every reflector in its line of sight (docs/planner.md)");
  AddOptionFlags(init, TrackerSettingsOptions(), options->tracker, &options->flags, "tracker-");
  init->add_flag("--json", options->json, "print one JSON object on stdout");
  init->callback([=] { *exit_code = RunSessionInit(*options, std::cout, std::cerr); });
  AddSessionRecord(session, exit_code);
  AddSessionStatus(session, exit_code);
  AddSessionCheckNoise(session, exit_code);
}

}  // namespace hexcal::cli
