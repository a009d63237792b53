// Inside the calibration from pixels (pixel_calibration.h): from the solved
// problem to the result — residual figures, the covariance of the 42
// parameters and the camera and target quantities with the platform poses
// eliminated (Schur complement of JᵀJ), the σ and correlations.
#pragma once

#include <ceres/ceres.h>

#include <array>
#include <vector>

#include "vision/pixel_calibration_types.h"
#include "vision/pixel_calibration_cost.h"

namespace hexcal {

// A camera or target block of the problem and whether the fit moved it.
struct EstimatedBlock {
  const char* name;  // "focal", "principal", "target_scale"
  double* data;
  int size;
  bool estimated;
};

struct PixelFit {
  ceres::Problem* problem = nullptr;
  std::array<LegParameters, kNumLegs>* legs = nullptr;
  std::vector<Vector6d>* poses = nullptr;
  std::vector<EstimatedBlock> estimated;
  std::vector<TagCornersResidual> tags;  // copies, to measure the unwhitened reprojection error
  std::array<std::vector<ceres::ResidualBlockId>, kNumLegs> leg_rows;
  std::array<std::vector<int>, kNumLegs> leg_images;  // the image of each of leg_rows
};

// The result without the fields the solve itself fills (poses, camera,
// iterations). Fails when the parameters are not identifiable from the data
// (a singular reduced information matrix).
StatusOr<PixelCalibrationResult> SummarizePixelFit(const PixelCalibrationInput& input, const PixelFit& fit,
                                                   const PixelCalibrationOptions& options);

}  // namespace hexcal
