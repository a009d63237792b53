// Outlier screening of the per-leg calibration fits (docs/calibration.md,
// "Outliers"): one bad leg reading is named and left out instead of bending
// its leg's parameters.
//
// With weighted residuals r_ij = F_ij / w_ij (calibration.h; w_ij the standard
// deviation of F_ij under the noise model and the image's pose covariance) a
// correct row has |r_ij| ≈ 1. Leg i is fitted by weighted least squares, then
// with a Cauchy loss of scale c = 3 standard deviations, from the nominal
// parameters and from the least-squares estimate, keeping the lower robust
// cost (and refitted at c = 3 ŝ_i when ŝ_i > 1). A single far-off row cannot
// pull that fit: its residual stays visible instead of being shared with its
// neighbours. At the robust fit
//   z_ij = −r_ij   (positive: the reading is longer than the pose implies)
// and row j is an outlier of leg i when
//   |z_ij| > threshold · max(1, ŝ_i),   ŝ_i = 1.4826 · median_j |z_ij| · √(N / (N − 7)),
// ŝ_i being a robust estimate of the leg's scatter in σ (median absolute
// value, corrected for the 7 fitted parameters): a noise model that is too
// optimistic raises the bar instead of flagging every row.
//
// Threshold: with Gaussian residuals P(|z| > 5) = 5.7e-7 per row, so over the
// 6 N tests of a session (N ≤ 500 images, 3000 tests) the chance of one false
// alarm is at most 1.7e-3 (8e-5 for 24 images). Residuals of a fit are
// smaller than the noise (leverage), which only lowers that rate. One σ of a
// reading is about 0.001 cm on the demo robots (σ_F / 2ℓ), so errors from
// about 0.01 cm are found.
//
// A leg needs kMinRowsToScreen rows: with fewer than 3 redundant equations
// the robust fit can explain any one row away, so it cannot tell which is off
// (a leg with fewer rows is fitted as without screening).
//
// This file has the statistics and the options; the screened fit of a leg,
// which uses them, is CalibrateLegScreened (calibration_leg.h).
//
//   CalibrationOptions options;   // weighted, as in a session
//   options.outliers.enabled = true;
//   StatusOr<CalibrationResult> r = Calibrate(nominal, measurements, options);
//   for (const RowOutlier& o : r->legs[2].outliers) Print(o.measurement, o.residual, o.z);
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/inverse_kinematics.h"
#include "core/option_spec.h"

namespace hexcal {

struct OutlierScreening {
  bool enabled = false;  // screen every leg's rows (needs weighted residuals)
  double threshold = 5;  // |z| above which a row is an outlier, in standard deviations
  bool keep = false;     // keep the flagged rows in the final fit (they are still reported)

  bool IsValid(std::string* error) const;
};

constexpr int kMinRowsToScreen = 10;         // 7 parameters + 3 redundant equations
constexpr double kScreeningCauchyScale = 3;  // σ; Cauchy is 95 % efficient on Gaussian data from 2.385 σ up

// `outlier_threshold` (--outlier-threshold, 3..100) and `keep_outliers`
// (--keep-outliers), described once (core/option_spec.h) for the CLI and docs/cli.md.
const OptionTable<OutlierScreening>& OutlierScreeningOptions();

// One row of one leg that failed the screening.
struct RowOutlier {
  int measurement = 0;    // index into the calibration's measurements, from 0
  double residual = 0;    // (L + l) − |P + R b − a| at the robust fit, robot unit
  double z = 0;           // the same in standard deviations of the noise model
  bool excluded = false;  // left out of the leg's final fit
};

// ŝ = 1.4826 · median |z| · √(N / (N − parameters)) (see above); 0 for no rows.
double RobustScatter(const std::vector<double>& z, int parameters);

// The rows j with |z_j| > threshold · max(1, RobustScatter(z)), ascending.
std::vector<int> FlagOutliers(const std::vector<double>& z, int parameters, double threshold);

// The screening of a joint fit's readings (the calibrations from pixels and
// from points): `leg_z` the z = −r of every measurement's readings at the
// robust fit (a Cauchy loss of kScreeningCauchyScale σ_L), σ_L = `sigma`; per
// leg with kMinRowsToScreen rows or more, the readings with
// |z| > threshold · max(1, ŝ_i), excluded unless `keep`.
std::array<std::vector<RowOutlier>, kNumLegs> ScreenJointFitReadings(const std::vector<LegReadings>& leg_z,
                                                                     const OutlierScreening& screening, double sigma);

}  // namespace hexcal
