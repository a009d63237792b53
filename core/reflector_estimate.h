// The reflectors' positions in a frame fixed to the platform, estimated from
// the measured point sets themselves (issue 38, docs/calibration.md, "Point
// measurements"), for a session that has no reflector file: the platform
// carries the reflectors rigidly, so every pose sees the same shape, moved.
//
// Generalised Procrustes: the set with the most points is the first estimate;
// each round fits every set that shares 3 or more reflectors with the
// estimate (core/point_fit.h), maps all its points back into the estimate's
// frame and averages them by name, until the estimate moves less than 1e-9 of
// its size. The frame stays the first set's (the tracker's at that pose); the
// registration estimates platform_from_target, so any frame fixed to the
// platform will do.
//
//   StatusOr<std::vector<NamedPoint>> reflectors = EstimateReflectors(sets);
#pragma once

#include <vector>

#include "core/point_file.h"
#include "core/status.h"

namespace hexcal {

// Bad input when no set holds 3 points; sets that cannot be fitted (an
// outlier, too few shared reflectors) are left out of the average.
StatusOr<std::vector<NamedPoint>> EstimateReflectors(const PointSets& sets);

}  // namespace hexcal
