// Child processes of the LinuxCNC tools: halcmd (devices/hal_push.h) and
// the machine status reader (sim/machine_follower.h). The child's
// standard output (and its standard error, unless discarded) goes into one
// end of a socket pair; the caller reads the other, with time-outs
// (LineClient::Adopt) or to the end.
//
//   StatusOr<ChildProcess> child = SpawnWithOutputSocket({"halcmd", "-f", "x.hal"}, false);
//   ... read child->fd ...; close(child->fd);
//   int status = WaitChild(child->pid);
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

#include "core/status.h"

namespace hexcal::workflow {

struct ChildProcess {
  pid_t pid = -1;
  int fd = -1;  // the parent's end of the socket pair: the caller closes it
};

// Starts argv (argv[0] searched in PATH). Errors name the program and say
// whether it is missing.
StatusOr<ChildProcess> SpawnWithOutputSocket(const std::vector<std::string>& argv, bool discard_stderr);

// Waits for the child to end: its exit code, or 128 + the signal that ended it.
int WaitChild(pid_t pid);

}  // namespace hexcal::workflow
