// Which capture belongs to which planned pose (issue 35): by content, not by
// the image's name. A capture of the Acquire step (`hexcal acquire`, the
// GUI's Acquire step) records the pose it was commanded to in legs.csv
// (commanded_x..commanded_q3, core/session.h); a planned pose is recorded
// when a row with its image present holds that pose. So after a new plan an
// old pose_0000.png does not count for the new plan's pose 1, and a new
// capture of that pose gets a free name (pose_0000_2.png) when the old one is
// kept. A row written before legs.csv held commanded poses counts for pose k
// when it is named pose_000k.png and its readings agree with the nominal IK
// of the pose within the typed-reading tolerance (reading_check.h).
//
// Replanning over recorded poses (the GUI's Plan step) asks what becomes of
// the captures the new plan leaves without their pose: kept (still images
// with readings the calibration uses), archived (moved with their rows to
// SESSION/archive/captures-TIMESTAMP/), or discarded.
//
//   StatusOr<std::vector<ReadingsRow>> rows = ReadReadingsTable("run1");
//   std::vector<int> row_of_pose = CapturesOfPlan(check, plan, *rows);  // -1: to do
//   std::string name = CaptureImageName(3, *rows);                        // "pose_0003.png"
#pragma once

#include <string>
#include <vector>

#include "core/pose.h"
#include "core/status.h"
#include "session/readings_table.h"
#include "workflow/reading_check.h"

namespace hexcal::workflow {

// "pose_0007.png": the image of plan row `pose_index` as the Acquire step
// names it first (CaptureImageName when the name is taken).
std::string AcquiredImageName(int pose_index);

// "pose_0007": the name a points session gives plan row `pose_index` in
// legs.csv and in the points file (the tracker's group), first.
std::string AcquiredPoseName(int pose_index);

// Two commanded poses are the same pose: plan.csv and legs.csv hold the same
// number text (an exact round trip); 1e-9 relative for other writers.
bool SameCommandedPose(const Vector6d& a, const Vector6d& b);

// The row of `rows` recorded at `pose` (plan row `pose_index`), or -1: a row
// of legs.csv, whether its image is there or not (the GUI marks a pose
// recorded only with its image).
int CaptureOfPose(const ReadingCheck& check, int pose_index, const Vector6d& pose,
                  const std::vector<ReadingsRow>& rows);
// CaptureOfPose of every plan row.
std::vector<int> CapturesOfPlan(const ReadingCheck& check, const std::vector<Vector6d>& plan,
                                const std::vector<ReadingsRow>& rows);

// The image name a new capture of plan row `pose_index` gets:
// AcquiredImageName (pose_0007.png) unless legs.csv has a row of that name
// (another pose's capture, kept after a new plan), then pose_0007_2.png, ...
std::string CaptureImageName(int pose_index, const std::vector<ReadingsRow>& rows);
// The same for a points session's row: pose_0007, else pose_0007_2, ...
std::string CapturePoseName(int pose_index, const std::vector<ReadingsRow>& rows);

// The images recorded at a pose of `old_plan` that is in no row of
// `new_plan`: the captures a new plan leaves without their pose.
std::vector<std::string> CapturesLeftByPlan(const ReadingCheck& check, const std::vector<Vector6d>& old_plan,
                                            const std::vector<Vector6d>& new_plan,
                                            const std::vector<ReadingsRow>& rows);

enum class CaptureDisposal { kKeep, kArchive, kDiscard };
const char* CaptureDisposalName(CaptureDisposal disposal);  // "keep", "archive", "discard"

// The images and their legs.csv rows moved into a new folder
// SESSION/archive/captures-YYYYMMDDTHHMMSSZ/ (images/ and a legs.csv of their
// rows), under the session lock; returns the folder. The session then no
// longer has them: the calibration does not use them; moving them back
// (both the images and the rows) restores them.
StatusOr<std::string> ArchiveCaptures(const std::string& session_dir, const std::vector<std::string>& images);
// The images and their rows removed (RemoveCapture of each).
Status DiscardCaptures(const std::string& session_dir, const std::vector<std::string>& images);

}  // namespace hexcal::workflow
