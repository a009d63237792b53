// Files of point measurements (issue 38, docs/calibration.md, "Point
// measurements"): named 3D points per pose, as a laser tracker's software
// exports them, in the robot's length unit.
//
// CSV, with a header: `pose,point,x,y,z` and optionally `sigma` (each
// coordinate's standard deviation); any column order, other columns ignored.
//
// SpatialAnalyzer's ASCII export: one point a line, `collection group target
// x y z [sigma]`, separated by spaces, tabs or commas; the group is the pose,
// the target the reflector; blank lines and lines starting with `//` or `#`
// are skipped.
//
// A point without a σ gets `default_sigma`. Errors name the source and line:
// a missing column or field, a cell that is not a number, a σ not positive, a
// point given twice in one pose.
//
//   StatusOr<PointSets> sets = ParsePointFile(text, "points.csv", 0.02);
//   for (const PointSet& set : *sets) FitPointPose(reflectors, set.points);
#pragma once

#include <string>
#include <vector>

#include "core/point_fit.h"
#include "core/status.h"

namespace hexcal {

struct PointSet {
  std::string pose;  // the pose's name: legs.csv's row, or the tracker's group
  std::vector<NamedPoint> points;
};
using PointSets = std::vector<PointSet>;  // in the order poses first appear

// Either layout: CSV when the first line that is not a comment names the
// columns `pose` and `point` (after any byte-order mark), else SpatialAnalyzer's.
StatusOr<PointSets> ParsePointFile(const std::string& text, const std::string& source, double default_sigma);

// The reflectors' positions in the reflector frame: CSV `point,x,y,z`.
// Errors as above, and a name given twice.
StatusOr<std::vector<NamedPoint>> ParseReflectorFile(const std::string& text, const std::string& source);

// The same read from `path` (a table's size limit, core/atomic_file.h), its
// errors naming `source` (the path when empty).
StatusOr<PointSets> LoadPointFile(const std::string& path, double default_sigma, const std::string& source = "");
StatusOr<std::vector<NamedPoint>> LoadReflectorFile(const std::string& path, const std::string& source = "");

}  // namespace hexcal
