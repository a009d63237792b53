// The readings table as the operator edits it (the GUI's Measure and Acquire
// steps): every row of legs.csv as its cells read, even when the session's
// rows do not load (an image without a row makes LoadSessionLegs refuse the
// file), and a blank row for every image in images/ that has no readings yet,
// so that there is always a row to type or paste the six readings into.
// In a points session the rows are keyed by legs.csv's `pose` column, and
// the blank rows are the points file's poses without readings.
//
//   StatusOr<std::vector<ReadingsRow>> rows = ReadReadingsTable("run1");
//   for (const ReadingsRow& row : *rows) if (!row.recorded) ...;  // to type
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/pose.h"
#include "core/robot.h"
#include "core/status.h"

namespace hexcal::workflow {

struct ReadingsRow {
  std::string image;                                    // file name in images/; points sessions: the pose
  std::array<std::optional<double>, kNumLegs> legs{};   // a cell that is not a number: none
  bool holdout = false;
  bool recorded = false;       // legs.csv has a row for the image
  bool image_present = false;  // the image is in images/; points sessions: the points file has the pose
  // The pose the capture was commanded to (legs.csv's commanded_x..q3,
  // core/session.h); none for an image loaded or typed, or cells that do not read.
  std::optional<Vector6d> commanded{};
};

// Rows of legs.csv in file order, then the images (poses) without one, by
// name. A legs.csv that does not parse as CSV, or lacks a column, is an error.
StatusOr<std::vector<ReadingsRow>> ReadReadingsTable(const std::string& session_dir);

// Six readings from one pasted line: numbers separated by tabs, commas,
// semicolons or spaces (a spreadsheet's row, a terminal's output), with an
// optional leading image name. None when the line does not hold six numbers.
std::optional<std::array<double, kNumLegs>> ParseReadingsLine(const std::string& line);

}  // namespace hexcal::workflow
