#include "workflow/hal_push.h"

#include <unistd.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "workflow/child_process.h"

namespace hexcal::workflow {
namespace {

constexpr size_t kMaxOutputBytes = 1 << 16;
constexpr size_t kQuotedOutputChars = 300;

StatusOr<int> CountSetpLines(const std::string& hal_file) {
  std::ifstream in(hal_file);
  if (!in) return Status::Error(hal_file + ": cannot read the HAL file");
  std::ostringstream text;
  text << in.rdbuf();
  const int count = CountHalPins(text.str());
  if (count == 0) return Status::Error(hal_file + ": no setp lines: not a file of hexcal export --format linuxcnc-hal");
  return count;
}

// Runs argv to its end: the exit status and the output's last kMaxOutputBytes.
Status RunCapturing(const std::vector<std::string>& argv, int* exit_status, std::string* output) {
  StatusOr<ChildProcess> child = SpawnWithOutputSocket(argv, /*discard_stderr=*/false);
  if (!child.ok()) return Status::Error(child.status().message() + "; is LinuxCNC installed (linuxcnc-uspace)?");
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

int CountHalPins(const std::string& hal_text) {
  std::istringstream lines(hal_text);
  int count = 0;
  for (std::string line; std::getline(lines, line);) count += line.rfind("setp ", 0) == 0 ? 1 : 0;
  return count;
}

StatusOr<int> PushHalFile(const std::string& halcmd, const std::string& hal_file) {
  StatusOr<int> pins = CountSetpLines(hal_file);
  if (!pins.ok()) return pins.status();
  int exit_status = 0;
  std::string output;
  if (Status s = RunCapturing({halcmd, "-f", hal_file}, &exit_status, &output); !s.ok()) return s;
  if (exit_status != 0) {
    const std::string tail =
        output.size() > kQuotedOutputChars ? "..." + output.substr(output.size() - kQuotedOutputChars) : output;
    return Status::Failed(halcmd + " -f " + hal_file + " exited " + std::to_string(exit_status) +
                          " (is the machine running, and are RTAPI_UID and RTAPI_FIFO_PATH the machine's?): " + tail);
  }
  return *pins;
}

std::string HomeOffsetShifts(const Robot& running, const Robot& calibrated, MachineUnit unit) {
  const double scale = MachineUnitsPerRobotUnit(calibrated, unit);
  std::ostringstream out;
  for (int i = 0; i < kNumLegs; ++i) {
    const double shift = (calibrated.legs[i].offset - running.legs[i].offset) * scale;
    if (std::abs(shift) <= 1e-9) continue;
    // Six decimals: 1 nm on a mm machine, below any encoder.
    out << "[JOINT_" << i << "] HOME and HOME_OFFSET: add " << FixedNumber(shift, 6) << " " << MachineUnitName(unit)
        << " (leg " << i + 1 << ": l " << FixedNumber(running.legs[i].offset * scale, 6) << " -> "
        << FixedNumber(calibrated.legs[i].offset * scale, 6) << ")\n";
  }
  return out.str();
}

}  // namespace hexcal::workflow
