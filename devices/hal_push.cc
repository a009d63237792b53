#include "devices/hal_push.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "core/atomic_file.h"
#include "devices/child_process.h"

namespace hexcal::workflow {
namespace {

constexpr size_t kMaxOutputBytes = 1 << 16;
constexpr size_t kQuotedOutputChars = 300;

// Runs argv to its end: the exit status and the output's last kMaxOutputBytes.
Status RunCapturing(const std::vector<std::string>& argv, int* exit_status, std::string* output) {
  StatusOr<ChildProcess> child = SpawnWithOutputSocket(argv, /*discard_stderr=*/false);
  if (!child.ok()) return child.status().WithHint("; is LinuxCNC installed (linuxcnc-uspace)?");
  char buffer[4096];
  for (ssize_t got; (got = read(child->fd, buffer, sizeof buffer)) > 0;) {
    output->append(buffer, static_cast<size_t>(got));
    if (output->size() > kMaxOutputBytes) output->erase(0, output->size() - kMaxOutputBytes);
  }
  close(child->fd);
  *exit_status = WaitChild(child->pid);
  return Status::Ok();
}

}  // namespace

StatusOr<std::string> RunHalText(const std::string& halcmd, const std::string& hal_text) {
  char path[] = "/tmp/hexcal-hal.XXXXXX";
  const int fd = mkstemp(path);
  if (fd < 0) return Status::IoError("cannot make a temporary HAL file in /tmp");
  const bool written = write(fd, hal_text.data(), hal_text.size()) == static_cast<ssize_t>(hal_text.size());
  close(fd);
  int exit_status = 0;
  std::string output;
  Status ran = written ? RunCapturing({halcmd, "-f", path}, &exit_status, &output)
                       : Status::IoError("cannot write a temporary HAL file in /tmp");
  unlink(path);
  if (!ran.ok()) return ran;
  if (exit_status != 0) {
    const std::string tail =
        output.size() > kQuotedOutputChars ? "..." + output.substr(output.size() - kQuotedOutputChars) : output;
    return Status::Failed(halcmd + " exited " + std::to_string(exit_status) +
                          " (is the machine running, and are RTAPI_UID and RTAPI_FIFO_PATH the machine's?): " + tail);
  }
  return output;
}

StatusOr<std::vector<double>> ReadHalPins(const std::string& halcmd, const std::vector<std::string>& pins) {
  std::string text;
  for (const std::string& pin : pins) text += "getp " + pin + "\n";
  StatusOr<std::string> output = RunHalText(halcmd, text);
  if (!output.ok()) return output.status();
  std::istringstream lines(*output);
  std::vector<double> values;
  for (std::string line; std::getline(lines, line) && values.size() < pins.size();) {
    char* end = nullptr;
    const double value = std::strtod(line.c_str(), &end);
    if (end == line.c_str() || !std::isfinite(value))
      return Status::Failed(halcmd + ": getp " + pins[values.size()] + " gave no number");
    values.push_back(value);
  }
  if (values.size() != pins.size()) return Status::Failed(halcmd + ": fewer values than getp lines");
  return values;
}

StatusOr<std::array<double, 6>> HomeShifts(const Robot& running, const Robot& calibrated, MachineUnit unit) {
  const double running_scale = MachineUnitsPerRobotUnit(running, unit);
  const double scale = MachineUnitsPerRobotUnit(calibrated, unit);
  double size = 0;  // the running robot's, machine units
  for (const Leg& leg : running.legs) size = std::max({size, leg.a_in_base.norm(), leg.b_in_platform.norm()});
  size *= running_scale;
  std::array<double, 6> shifts{};
  for (int i = 0; i < kNumLegs; ++i) {
    const Leg &was = running.legs[i], &now = calibrated.legs[i];
    shifts[i] = now.offset * scale - was.offset * running_scale;
    const double moved = std::max({(now.a_in_base * scale - was.a_in_base * running_scale).norm(),
                                   (now.b_in_platform * scale - was.b_in_platform * running_scale).norm(),
                                   std::abs(shifts[i])});
    if (!(moved <= kSameMachineShare * size)) {
      return Status::BadInput("leg " + std::to_string(i + 1) + " of robot '" + CommentText(calibrated.name) + "' is " +
                              FixedNumber(moved, 6) + " " + MachineUnitName(unit) + " from the running robot '" +
                              CommentText(running.name) + "''s (more than " + FixedNumber(100 * kSameMachineShare) +
                              " % of its size): not the same machine, or a robot file in another length unit");
    }
  }
  return shifts;
}

}  // namespace hexcal::workflow
