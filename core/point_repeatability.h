// How well a point instrument repeats (issue 38, docs/calibration.md,
// "Repeatability check"): the same pose measured k times (k point sets of
// the same reflectors, the platform not moved), against the σ the points
// declare.
//
// The k sets share one shape (the reflectors, estimated as in
// core/reflector_estimate.h) and each has its own rigid motion (the tracker
// may be bumped between sets; a fixed pose is not assumed), so the scatter is
// the points' residuals after the fits: σ̂² = Σ|r|² / (3N − 6k − 3n + 6) for N
// points measured in k sets of n reflectors (the shape's 3n coordinates less
// its 6 free ones of frame).
//
//   StatusOr<Repeatability> r = MeasurePointRepeatability(sets);
//   r->ratio;  // measured / declared σ: near 1 when the declared noise is right
#pragma once

#include "core/point_file.h"
#include "core/status.h"

namespace hexcal {

struct Repeatability {
  int repeats = 0;             // point sets (or images) used
  int points = 0;              // reflectors (or board points) per set
  int degrees_of_freedom = 0;
  double measured_sigma = 0;   // of each coordinate, unit
  double declared_sigma = 0;   // the RMS of the σ the points state, unit
  double ratio = 0;            // measured / declared
};

// Bad input: fewer than 3 sets, a set that does not fit (named), or too few
// points for any degree of freedom.
StatusOr<Repeatability> MeasurePointRepeatability(const PointSets& sets);

}  // namespace hexcal
