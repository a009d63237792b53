#include "core/path_tracker.h"

#include <algorithm>

namespace hexcal {
namespace {

// x = A⁻¹ b by Gaussian elimination with partial pivoting, the pivot chosen on
// |re| + |im|: any norm gives a stable pivot, and this one needs no hypot
// (Eigen's PartialPivLU scores complex pivots by |·|, a fifth of the tracking
// time). A singular A gives non-finite entries, which the callers test.
CVector8 SolveLinear(CMatrix8 a, CVector8 b) {
  const auto score = [](const Complex& v) { return std::abs(v.real()) + std::abs(v.imag()); };
  for (int k = 0; k < kStudyUnknowns; ++k) {
    int pivot = k;
    for (int r = k + 1; r < kStudyUnknowns; ++r) {
      if (score(a(r, k)) > score(a(pivot, k))) pivot = r;
    }
    if (pivot != k) {
      a.row(k).swap(a.row(pivot));
      std::swap(b[k], b[pivot]);
    }
    const Complex inverse = 1.0 / a(k, k);
    for (int r = k + 1; r < kStudyUnknowns; ++r) {
      const Complex factor = a(r, k) * inverse;
      a.row(r).tail(kStudyUnknowns - k - 1) -= factor * a.row(k).tail(kStudyUnknowns - k - 1);
      b[r] -= factor * b[k];
    }
  }
  for (int k = kStudyUnknowns - 1; k >= 0; --k) {
    b[k] = (b[k] - Complex(a.row(k).tail(kStudyUnknowns - k - 1) * b.tail(kStudyUnknowns - k - 1))) / a(k, k);
  }
  return b;
}

// dz/ds = -H_z⁻¹ H_s
CVector8 Tangent(const Homotopy& homotopy, const CVector8& z, double s) {
  CVector8 hs;
  CMatrix8 hz;
  homotopy.Evaluate(z, s, nullptr, &hz, &hs);
  return -SolveLinear(hz, hs);
}

bool Correct(const Homotopy& homotopy, double s, CVector8* z, const TrackerOptions& options) {
  double previous = 0;
  for (int it = 0; it < options.max_corrector_iterations; ++it) {
    CVector8 h;
    CMatrix8 hz;
    homotopy.Evaluate(*z, s, &h, &hz, nullptr);
    const CVector8 dz = SolveLinear(hz, h);
    if (!dz.allFinite()) return false;
    *z -= dz;
    const double size = dz.norm(), scale = 1 + z->norm();
    if (size <= options.corrector_tolerance * scale) return true;
    // Demand fast (quadratic-like) contraction, or the prediction was off-path.
    if (it == 0 && size > 1e-2 * scale) return false;
    if (it > 0 && size > 0.25 * previous) return false;
    previous = size;
  }
  return false;
}

}  // namespace

PathEnd TrackPath(const Homotopy& homotopy, const CVector8& start, const TrackerOptions& options) {
  PathEnd end;
  end.z = start;
  double s = 1, step = options.initial_step;
  int successes = 0;
  while (s > 0 && end.steps < options.max_steps) {
    ++end.steps;
    const double ds = std::min(step, s);
    const double s_new = s - ds <= 1e-15 ? 0.0 : s - ds;
    const CVector8& z = end.z;
    const CVector8 k1 = Tangent(homotopy, z, s);
    const CVector8 k2 = Tangent(homotopy, z - 0.5 * ds * k1, s - 0.5 * ds);
    const CVector8 k3 = Tangent(homotopy, z - 0.5 * ds * k2, s - 0.5 * ds);
    const CVector8 k4 = Tangent(homotopy, z - ds * k3, s_new);
    CVector8 predicted = z - (ds / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    if (predicted.allFinite() && Correct(homotopy, s_new, &predicted, options)) {
      end.z = predicted;
      s = s_new;
      if (++successes >= 3) {
        step = std::min(2 * step, options.max_step);
        successes = 0;
      }
      if (end.z.norm() > options.divergence_norm) break;
      if (options.give_up && s > 0 && options.give_up(end.z, s)) break;
    } else {
      step *= 0.5;
      successes = 0;
      if (step < options.min_step) break;
    }
  }
  end.s = s;
  end.reached_end = s == 0;
  return end;
}

bool RefineAt(const Homotopy& homotopy, double s, CVector8* z, int iterations, double tolerance) {
  bool converged = false;
  for (int it = 0; it < iterations; ++it) {
    CVector8 h;
    CMatrix8 hz;
    homotopy.Evaluate(*z, s, &h, &hz, nullptr);
    const CVector8 dz = SolveLinear(hz, h);
    if (!dz.allFinite()) return false;
    *z -= dz;
    converged = dz.norm() <= tolerance * (1 + z->norm());
    if (converged && it > 0) break;
  }
  return converged;
}

}  // namespace hexcal
