// hexcal session init --robot R --camera C --target T DIR [--noise-position p]
//   [--noise-angle a] [--noise-leg l] [--json]
// hexcal session status DIR [--json]
// hexcal session record DIR --image NAME --legs L1,...,L6 [--from FILE] [--holdout] [--replace] [--wait] [--json]
#include <filesystem>
#include <iostream>
#include <memory>
#include <vector>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "app/commands/option_flags.h"
#include "core/csv.h"
#include "core/robot_io.h"
#include "core/session.h"
#include "vision/camera.h"
#include "vision/target.h"
#include "workflow/session_edits.h"
#include "workflow/session_init.h"
#include "workflow/session_status.h"

namespace hexcal::cli {
namespace {

struct SessionInitOptions {
  std::string dir;
  SessionConfig config;
  bool json = false;
  std::shared_ptr<OptionEntries> noise = std::make_shared<OptionEntries>();  // --noise-*
};

int RunSessionInit(SessionInitOptions cli, std::ostream& out, std::ostream& err) {
  if (Status s = ApplyOptionEntries(NoiseModelOptions(), *cli.noise, &cli.config.noise, "noise"); !s.ok())
    return ReportError(err, "session init", s);
  // The names load now rather than at the first calibration; nothing is
  // created when one does not (workflow/session_init.h).
  if (Status s = workflow::CreateSession(cli.dir, cli.config); !s.ok()) return ReportError(err, "session init", s);
  const SessionPaths paths(cli.dir);
  if (cli.json) {
    out << JsonText({{"session", cli.dir}, {"config", paths.config}, {"images", paths.images}});
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
    return Status::Error(paths.images + "/" + Excerpt(image) + ": no such image; put it there first, or give --from");
  return CheckFileForReading(path.string(), kMaxImageBytes);
}

// One row of legs.csv, written under the session lock into legs.csv as it is
// on disk (workflow/session_edits.h): rows others wrote are kept.
int RunSessionRecord(const SessionRecordOptions& cli, std::ostream& out, std::ostream& err) {
  const SessionPaths paths(cli.dir);
  StatusOr<std::vector<double>> legs = ParseNumberList(cli.legs, kNumLegs, "--legs");
  if (!legs.ok()) return ReportError(err, "session record", legs.status());
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
    return ReportError(err, "session record", Status::Error(done.conflict_text + "; use --replace to replace it"));
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

}  // namespace

void AddSessionCommand(CLI::App& app, int* exit_code) {
  CLI::App* session =
      app.add_subcommand("session", "create a session folder, record readings, show its status (docs/session.md)");
  session->require_subcommand(1);
  auto options = std::make_shared<SessionInitOptions>();
  CLI::App* init = session->add_subcommand("init", "create DIR with session.yaml, images/ and results/");
  init->add_option("dir", options->dir, "session folder")->required();
  init->add_option("--robot", options->config.robot, "nominal robot file or preset name")->required();
  init->add_option("--camera", options->config.camera, "camera file (hexcal intrinsics)")->required();
  init->add_option("--target", options->config.target, "target file or name")->required();
  AddOptionFlags(init, NoiseModelOptions(), options->noise, "noise-");
  init->add_flag("--json", options->json, "print one JSON object on stdout");
  init->callback([=] { *exit_code = RunSessionInit(*options, std::cout, std::cerr); });
  AddSessionRecord(session, exit_code);
  AddSessionStatus(session, exit_code);
}

}  // namespace hexcal::cli
