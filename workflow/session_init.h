// A new session folder, as `hexcal session init` and the GUI's File > New
// session make it (docs/session.md): the robot, camera and target are loaded
// first, and nothing is created when one does not load (issue 35: the GUI
// left a folder and session.yaml behind for a robot file that did not load,
// and a retry then said it existed). Names of files that exist are kept
// relative to the session folder, so the session works from any directory.
//
//   if (Status s = CreateSession("run1", {"inria-left-hand", "camera.yaml", "aprilgrid-6x6"}); !s.ok()) ...;
#pragma once

#include <string>

#include "core/session.h"
#include "core/status.h"

namespace hexcal::workflow {

// `name` as session.yaml keeps it: relative to `dir` when a file of that name
// exists (from the current directory), else as it is (a preset name).
std::string AsSessionPath(const std::string& dir, const std::string& name);

// Loads the robot, camera and target `config` names (an error names the one
// that does not load, and nothing is written), then InitSession with their
// names made AsSessionPath. A points session has no camera or target; its
// points and reflector files are kept as given (the points file may be
// written later; `hexcal session init` and the GUI's dialog check and place
// them).
Status CreateSession(const std::string& dir, SessionConfig config);

}  // namespace hexcal::workflow
