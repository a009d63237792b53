// Predictor-corrector path tracking for homotopy continuation in C^8.
//
// A homotopy H(z, s) = 0 defines solution paths z(s) from s = 1 (known start
// solutions) to s = 0 (the system we want). Each step predicts with RK4 on
// dz/ds = -H_z⁻¹ H_s and corrects with Newton at the new s; the step doubles
// after three accepted steps and halves after a rejected one. A path fails when
// the step falls below min_step (a singular end point, e.g. a spurious Δ = 0
// solution) or when z runs away.
#pragma once

#include <functional>

#include "core/study_system.h"

namespace hexcal {

class Homotopy {
 public:
  virtual ~Homotopy() = default;
  // H(z, s), dH/dz and dH/ds; h, hz or hs may be null when not needed.
  virtual void Evaluate(const CVector8& z, double s, CVector8* h, CMatrix8* hz, CVector8* hs) const = 0;
};

struct TrackerOptions {
  double initial_step = 0.05;
  double max_step = 0.25;
  double min_step = 1e-10;
  double corrector_tolerance = 1e-10;  // relative to 1 + |z|
  int max_corrector_iterations = 3;
  int max_steps = 20000;
  double divergence_norm = 1e8;
  // Optional: stop a path early (as failed) when this returns true at an
  // accepted point, e.g. once it is clearly heading for a spurious end.
  std::function<bool(const CVector8& z, double s)> give_up;
};

struct PathEnd {
  CVector8 z;
  bool reached_end = false;  // tracked all the way to s = 0
  double s = 1;              // where tracking stopped
  int steps = 0;
};

PathEnd TrackPath(const Homotopy& homotopy, const CVector8& start, const TrackerOptions& options = {});

// Newton's method on H(., s) at fixed s. Returns true if the last update was
// below tolerance·(1 + |z|); *z holds the refined point either way.
bool RefineAt(const Homotopy& homotopy, double s, CVector8* z, int iterations, double tolerance);

}  // namespace hexcal
