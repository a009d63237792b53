// The session's files as the Acquire step writes them (workflow/acquire_step.h,
// docs/acquisition.md, "Resuming"): which images have their legs.csv row, an
// image and its row written with the pending name that tells acquire's own
// interrupted capture from an operator's file, and the check that a session
// takes captures before any device is opened.
//
//   if (Status s = CheckSessionTakesCaptures("run1"); !s.ok()) return s;  // before the machine moves
//   if (Status s = ClearImageSlot("run1", "pose_0003.png", false, hooks); !s.ok()) ...;  // an operator's file
//   Status written = RecordWithPendingName("run1", png, row, LockWait::kNo);
#pragma once

#include <set>
#include <string>

#include "core/job_hooks.h"
#include "core/session.h"
#include "core/session_lock.h"
#include "core/status.h"

namespace hexcal::workflow {

// The images that have a row in legs.csv (none without legs.csv).
StatusOr<std::set<std::string>> ImagesWithRows(const std::string& session_dir);
// OK when images/IMAGE may be written: no file there, or the image a killed
// capture of acquire left (named in SESSION/.acquire-pending), which is
// removed when `remove`. Any other file is an operator's: bad input naming it.
Status ClearImageSlot(const std::string& session_dir, const std::string& image, bool remove, const JobHooks& hooks);
// RecordCaptureBytes with SESSION/.acquire-pending naming the image from
// before the image is written until its row is.
Status RecordWithPendingName(const std::string& session_dir, const std::string& png, const LegsRow& row, LockWait wait);
// legs.csv parses and images/ takes a new file (made and removed).
Status CheckSessionTakesCaptures(const std::string& session_dir);

}  // namespace hexcal::workflow
