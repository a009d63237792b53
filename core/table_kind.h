// Which of hexcal's CSV tables a header belongs to, so that a file given to
// the wrong command is named for what it is, with the command that takes it
// (issue 39). hexcal writes three tables with pose columns x..q3 that a user
// can mix up (docs/conventions.md, "Files"):
//   robot measurements  x,y,z,q1,q2,q3,L1..L6: base-frame poses with leg
//                       readings (calibrate --measurements, validate)
//   camera poses        file,x,...,status,...: camera_from_target per image
//                       (measure --out, a session's camera_poses.csv)
//   leg readings        image,L1..L6[,holdout]: a session's legs.csv
//   pose list           x,y,z,q1,q2,q3 alone (candidates --out; ik, indices --poses)
//
//   StatusOr<int> column = ColumnIndex(table, "L1");
//   if (!column.ok())
//     return Status::BadInput(column.status().message() + TableKindHint(table.header, TableKind::kRobotMeasurements));
#pragma once

#include <string>
#include <vector>

namespace hexcal {

enum class TableKind { kUnknown, kRobotMeasurements, kCameraPoses, kLegReadings, kPoseList };

TableKind KindOfTable(const std::vector<std::string>& header);

// "; this is a table of camera poses (...), which `hexcal ...` takes; ..." when
// `header` is one of hexcal's tables other than `wanted`; empty otherwise.
std::string TableKindHint(const std::vector<std::string>& header, TableKind wanted);

}  // namespace hexcal
