#include "core/table_kind.h"

#include <algorithm>

namespace hexcal {

namespace {

bool Has(const std::vector<std::string>& header, const std::string& column) {
  return std::find(header.begin(), header.end(), column) != header.end();
}

bool HasPose(const std::vector<std::string>& header) {
  for (const char* name : {"x", "y", "z", "q1", "q2", "q3"})
    if (!Has(header, name)) return false;
  return true;
}

bool HasLegs(const std::vector<std::string>& header) {
  for (const char* name : {"L1", "L2", "L3", "L4", "L5", "L6"})
    if (!Has(header, name)) return false;
  return true;
}

}  // namespace

TableKind KindOfTable(const std::vector<std::string>& header) {
  // `file` marks a table of images: measure's, or render's ground_truth.csv.
  if (Has(header, "file") && HasPose(header)) return TableKind::kCameraPoses;
  if (Has(header, "image") && HasLegs(header)) return TableKind::kLegReadings;
  if (HasPose(header) && HasLegs(header)) return TableKind::kRobotMeasurements;
  if (HasPose(header)) return TableKind::kPoseList;
  return TableKind::kUnknown;
}

std::string TableKindHint(const std::vector<std::string>& header, TableKind wanted) {
  const TableKind kind = KindOfTable(header);
  if (kind == wanted) return "";
  switch (kind) {
    case TableKind::kCameraPoses:
      return "; this is a table of camera poses (camera_from_target per image, in the camera frame, as `hexcal "
             "measure` writes it), not robot measurements: to calibrate from images use `hexcal calibrate --session "
             "DIR`, whose results/calibration_measurements.csv holds robot measurements (base-frame poses with "
             "readings L1..L6)";
    case TableKind::kLegReadings:
      return "; this is a session's leg readings (legs.csv: image, L1..L6) without poses: `hexcal calibrate "
             "--session DIR` measures the poses in the images";
    case TableKind::kPoseList:
      return "; this is a list of poses without leg readings (as `hexcal candidates` writes it), which "
             "`hexcal ik`, `indices` and `simulate --sets` take; `hexcal ik --out` adds the readings of a robot";
    case TableKind::kRobotMeasurements:
    case TableKind::kUnknown:
      break;
  }
  return "";
}

}  // namespace hexcal
