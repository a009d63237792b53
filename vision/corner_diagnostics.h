// Per-corner diagnostics of a fit that reprojects target corners (the
// calibration from pixels, pixel_calibration.h; the intrinsics, intrinsics.h),
// as Kalibr and mrcal give them (docs/calibration.md, "Per-corner
// diagnostics"): every corner's residual, the worst ones named, the
// distribution of |residual| against what noise alone would give, and where
// in the image corners were seen at all.
//
// Noise model: a corner's residual r = projected − observed is taken as
// N(0, σ² I₂) per axis. Then |r| follows the Rayleigh distribution,
//   P(|r| ≤ x) = 1 − exp(−x² / 2σ²),  median σ √(2 ln 2)
// (Papoulis & Pillai, Probability, 4th ed., section 6-2), which the histogram
// is compared with.
//
//   std::vector<CornerResidual> worst = WorstCorners(fit.corner_residuals, 10);
//   ResidualHistogram h = HistogramOfResiduals(fit.corner_residuals, RobustAxisSigma(fit.corner_residuals));
//   CoverageGrid grid = CountCorners(fit.corner_residuals, camera.width, camera.height);
#pragma once

#include <Eigen/Core>
#include <vector>

namespace hexcal {

struct CornerResidual {
  int image = 0;                                       // index into the fit's list of images
  int tag_id = 0;                                      // the target's tag id
  int corner = 0;                                      // 0..3, AprilTag order (docs/conventions.md)
  Eigen::Vector2d observed = Eigen::Vector2d::Zero();  // the detected corner, pixels
  Eigen::Vector2d residual = Eigen::Vector2d::Zero();  // projected − observed, pixels
};

// The k corners of largest |residual|, largest first; equal ones in input order.
std::vector<CornerResidual> WorstCorners(const std::vector<CornerResidual>& corners, int k);

// σ per axis from the median |r| (Rayleigh median σ √(2 ln 2)): the fit's own
// noise, not inflated by the few outliers the diagnostics look for. 0 when empty.
double RobustAxisSigma(const std::vector<CornerResidual>& corners);

// Fraction of |r| in [a, b) for N(0, σ² I₂): exp(−a²/2σ²) − exp(−b²/2σ²).
double RayleighFraction(double a, double b, double sigma);

struct ResidualHistogram {
  double sigma = 0;              // per-axis σ expected, pixels (> 0)
  double bin_width = 0;          // pixels; bin b holds |r| in [b w, (b + 1) w)
  std::vector<int> counts;       // corners per bin
  std::vector<double> expected;  // corners per bin that noise of σ gives (Rayleigh)
  int beyond = 0;                // corners at or past the last bin's end
  double expected_beyond = 0;    // ... and how many noise of σ puts there
};

// `bins` equal bins from 0 to 6σ (σ/4 wide for the default 24); sigma > 0, bins > 0.
ResidualHistogram HistogramOfResiduals(const std::vector<CornerResidual>& corners, double sigma, int bins = 24);

// Corners counted in a cols × rows grid over a width × height image; a
// corner on a cell's left or top edge is in that cell, one outside the image
// in the nearest cell.
struct CoverageGrid {
  int cols = 0, rows = 0;
  double width = 0, height = 0;  // pixels
  std::vector<int> counts;       // row-major, row 0 at the image's top

  int At(int row, int col) const { return counts[static_cast<size_t>(row * cols + col)]; }
  int EmptyCells() const;
};

CoverageGrid CountCorners(const std::vector<CornerResidual>& corners, double width, double height, int cols = 8,
                          int rows = 6);

}  // namespace hexcal
