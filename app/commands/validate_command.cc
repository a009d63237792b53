// hexcal validate --robot R --measurements M.csv [--noise-position p] [--noise-angle a] [--noise-leg l] [--json]
//   (workflow/validate_step.h)
#include <iostream>
#include <memory>

#include "app/commands/cli_common.h"
#include "app/commands/command_table.h"
#include "app/commands/option_flags.h"
#include "core/noise_model.h"
#include "workflow/validate_step.h"

namespace hexcal::cli {
namespace {

int RunValidate(workflow::ValidateRequest request, const OptionEntries& noise, const OptionFlagNames& flags, bool json,
                std::ostream& out, std::ostream& err) {
  if (Status s = ApplyOptionEntries(NoiseModelOptions(), noise, &request.noise, "noise"); !s.ok())
    return ReportError(err, "validate", s);
  StatusOr<workflow::ValidateResult> result = workflow::ValidateMeasurements(request);
  if (!result.ok()) return ReportError(err, "validate", result.status(), flags);
  out << (json ? JsonText(workflow::ToJson(*result)) : workflow::FormatValidateSummary(*result));
  return kExitOk;
}

}  // namespace

void AddValidateCommand(CLI::App& app, int* exit_code) {
  auto request = std::make_shared<workflow::ValidateRequest>();
  auto json = std::make_shared<bool>(false);
  auto noise = std::make_shared<OptionEntries>();  // --noise-*: what the verdict compares the errors with
  auto flags = std::make_shared<OptionFlagNames>();
  CLI::App* sub = app.add_subcommand("validate", "forward-kinematics errors of a robot on measured poses");
  sub->add_option("--robot", request->robot, "robot file or preset name")->required();
  sub->add_option("--measurements", request->measurements, "measurements CSV: x,y,z,q1,q2,q3,L1..L6")->required();
  AddOptionFlags(sub, NoiseModelOptions(), noise, flags.get(), "noise-");
  sub->add_flag("--json", *json, "print one JSON object on stdout");
  sub->callback([=] { *exit_code = RunValidate(*request, *noise, *flags, *json, std::cout, std::cerr); });
}

}  // namespace hexcal::cli
