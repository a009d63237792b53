// The operator's edits of a session's recorded files (legs.csv, plan.csv, the
// camera in session.yaml), for the GUI and `hexcal session record` alike
// (issue 13, "the GUI never writes a stale copy"; docs/session.md).
//
// An edit is applied to the file as it is on disk now, under the session lock
// (core/session_lock.h): read, change what the operator changed, write
// atomically. Rows another program appended meanwhile are kept. When the value
// the operator changed is no longer what they saw (another program changed the
// same cell, the plan, the camera), nothing is written and the outcome is a
// conflict with a sentence saying what differs; the caller asks the operator
// and may apply the edit again with `overwrite`.
//
//   EditOutcome done = ApplyLegsEdit("run1", LegsEdit::SetReading("img_004.png", 2, 45.0, 45.012));
//   if (!done.status.ok()) ...; else if (done.conflict) AskTheOperator(done.conflict_text);
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/pose.h"
#include "core/session.h"
#include "core/session_lock.h"
#include "core/status.h"

namespace hexcal::workflow {

struct LegsEdit {
  enum class Kind { kSetReading, kSetHoldout, kSetRow };
  Kind kind = Kind::kSetRow;
  std::string image;  // the row's key: the image file name in images/, or in a points session its pose
  int leg = 0;        // kSetReading: 0..5 (L1..L6)
  // kSetReading, kSetHoldout: the value the operator saw; another value on
  // disk is a conflict. kSetRow: the row must not exist yet (else a conflict).
  double seen = 0;
  double value = 0;  // kSetReading: the reading; kSetHoldout: 0 or 1
  LegsRow row;       // kSetRow: the whole row (a capture)

  static LegsEdit SetReading(const std::string& image, int leg, double seen, double value);
  static LegsEdit SetHoldout(const std::string& image, bool seen, bool value);
  static LegsEdit SetRow(const LegsRow& row);
};

struct EditOptions {
  bool overwrite = false;  // apply even over a conflicting change on disk
  LockWait wait = LockWait::kBriefly;
};

struct EditOutcome {
  Status status;  // the edit could not be made: the file does not parse, the session is busy, a write failed
  bool conflict = false;
  std::string conflict_text;  // "legs.csv: L3 of img_004.png is '45.1' on disk, not 45 as shown ..."
};

EditOutcome ApplyLegsEdit(const std::string& session_dir, const LegsEdit& edit, const EditOptions& options = {});

// Refuses a folder of the session (e.g. "images") that leads out of it
// through a symbolic link: hexcal writes only inside the session folder.
// Reading through such a link is fine (images kept on another disk).
Status CheckWritableInside(const std::string& session_dir, const std::string& folder);

// A capture: the image file copied into images/ and its row added to
// legs.csv, both under one hold of the lock, so that no other step sees the
// image without its readings. The row is checked first; an image of that name
// already there is refused (recorded images are never replaced). A writer
// killed between the two writes leaves the image without a row, which
// LoadSessionLegs names ("images/x.png: no row in legs.csv").
EditOutcome RecordCapture(const std::string& session_dir, const std::string& image_file, const LegsRow& row,
                          const EditOptions& options = {});
// The same with the image file's contents in memory (a frame encoded as PNG
// by the Acquire step, workflow/acquire_step.h).
EditOutcome RecordCaptureBytes(const std::string& session_dir, const std::string& image_bytes, const LegsRow& row,
                               const EditOptions& options = {});

// In a points session legs.csv's rows are keyed by the column `pose`
// (core/session.h): the edits above find and write that column, and the
// captures below, which add images, are refused.

// legs.csv replaced by `legs_file` (the GUI's "Import readings"), under the
// lock; if the session's rows do not load with it, or a reading is not
// plausible (CheckTypedReadings, reading_check.h: the stroke, and the IK of
// the pose the image was captured at, from the file's commanded columns or
// the session's; the error names the file's line, the image, the leg and the
// value), the old legs.csv is put back (a kill in between leaves the imported
// file, which then fails to load with its error named).
Status ImportLegsFile(const std::string& session_dir, const std::string& legs_file);

// plan.csv becomes `wanted` (no file when empty); `seen` is the plan the
// operator's edit started from: plan.csv differing from it is a conflict.
EditOutcome ApplyPlanEdit(const std::string& session_dir, const std::vector<Vector6d>& seen,
                          const std::vector<Vector6d>& wanted, const EditOptions& options = {});

// session.yaml's camera becomes `wanted`; the other values stay as on disk
// (the file is written anew: comments and unknown keys are not kept).
EditOutcome ApplyCameraEdit(const std::string& session_dir, const std::string& seen, const std::string& wanted,
                            const EditOptions& options = {});

// A capture taken back (the Acquire step's Redo): its legs.csv row, then its
// image, under the lock. An image named in neither is bad input.
Status RemoveCapture(const std::string& session_dir, const std::string& image, LockWait wait = LockWait::kBriefly);

}  // namespace hexcal::workflow
