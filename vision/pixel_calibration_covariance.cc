#include "vision/pixel_calibration_covariance.h"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "core/joint_fit_information.h"

namespace hexcal {
namespace {

using Eigen::MatrixXd;

// The global blocks (legs, then the estimated camera and target blocks) and
// the pose blocks, in the column order of the Jacobian.
JointFitColumns Columns(const PixelFit& fit) {
  JointFitColumns columns;
  for (LegParameters& leg : *fit.legs) columns.blocks.push_back(leg.data());
  columns.global_columns = kNumParams;
  for (const EstimatedBlock& block : fit.estimated) {
    if (!block.estimated) continue;
    columns.blocks.push_back(block.data);
    columns.global_columns += block.size;
  }
  for (Vector6d& pose : *fit.poses) columns.blocks.push_back(pose.data());
  columns.poses = static_cast<int>(fit.poses->size());
  return columns;
}

// The unwhitened reprojection error of every corner (corner_diagnostics.h).
std::vector<CornerResidual> CornerResiduals(const PixelFit& fit) {
  const double focal = *fit.estimated[0].data, scale = *fit.estimated[2].data;
  const double* principal = fit.estimated[1].data;
  std::vector<CornerResidual> corners;
  for (const TagCornersResidual& tag : fit.tags) {
    TagCornersResidual plain = tag;
    plain.whitening.setIdentity();
    Eigen::Matrix<double, 8, 1> r = Eigen::Matrix<double, 8, 1>::Zero();
    plain((*fit.poses)[tag.image].data(), &focal, principal, &scale, r.data());
    for (int c = 0; c < 4; ++c)
      corners.push_back({tag.image, tag.tag_id, c, tag.observed.segment<2>(2 * c), r.segment<2>(2 * c)});
  }
  return corners;
}

double ReprojectionRms(const std::vector<CornerResidual>& corners) {
  double sum = 0;
  for (const CornerResidual& c : corners) sum += c.residual.squaredNorm();
  return corners.empty() ? 0 : std::sqrt(sum / static_cast<double>(corners.size()));
}

// σ_min / σ_max of the information with every unknown scaled to unit
// diagonal: 0 when a combination of unknowns is not seen by the data.
double ScaledConditionInverse(const MatrixXd& information) {
  const Eigen::VectorXd d = information.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  const MatrixXd scaled = d.asDiagonal() * information * d.asDiagonal();
  const Eigen::VectorXd eigen = Eigen::SelfAdjointEigenSolver<MatrixXd>(scaled).eigenvalues();
  return eigen[0] > 0 ? eigen[0] / eigen[eigen.size() - 1] : 0;
}

// Each leg's estimate with its σ, and its reading residuals r (in σ_L),
// evaluated once: their RMS (robot unit), z = −r of every reading used (NaN
// for the others), and the RMS over every leg.
void FillLegs(const PixelCalibrationInput& input, const PixelFit& fit, const MatrixXd& covariance,
              const PixelCalibrationOptions& options, double variance_factor, PixelCalibrationResult* result) {
  CalibrationResult& calibration = result->calibration;
  ParameterVector estimates;
  double leg_sum = 0;
  result->leg_z.assign(input.images.size(), LegReadings::Constant(std::nan("")));
  for (int i = 0; i < kNumLegs; ++i) {
    LegCalibration& leg = calibration.legs[i];
    leg.initial = LegParametersOf(input.nominal.legs[i]);
    FillLegUncertainty(i, (*fit.legs)[i], covariance, variance_factor, &leg);
    estimates.segment<kParamsPerLeg>(kParamsPerLeg * i) = leg.estimate;
    const std::vector<double> r = ResidualsOf(fit.problem, fit.leg_rows[i]);
    double sum = 0;
    for (size_t k = 0; k < r.size(); ++k) {
      sum += r[k] * r[k];
      result->leg_z[fit.leg_images[i][k]][i] = -r[k];
    }
    leg.residual_rms = r.empty() ? 0 : options.leg_sigma * std::sqrt(sum / r.size());
    leg.rows_used = static_cast<int>(r.size());
    leg_sum += std::pow(leg.residual_rms, 2) * r.size();
    result->leg_rows += leg.rows_used;
  }
  calibration.robot = WithParameters(input.start, estimates);
  calibration.num_measurements = static_cast<int>(input.images.size());
  result->leg_residual_rms = result->leg_rows > 0 ? std::sqrt(leg_sum / result->leg_rows) : 0;
}

// The camera and target estimates with σ, in the order of the columns after the 42 parameters.
void FillExtras(const PixelCalibrationInput& input, const PixelFit& fit, const MatrixXd& covariance,
                PixelCalibrationResult* result) {
  const Camera& file = input.camera;
  const double focal = *fit.estimated[0].data;
  result->camera = file;
  result->camera.fx = focal * file.fx;
  result->camera.fy = focal * file.fy;
  result->camera.cx = fit.estimated[1].data[0];
  result->camera.cy = fit.estimated[1].data[1];
  result->target_scale = *fit.estimated[2].data;
  int column = kNumParams;
  for (const EstimatedBlock& block : fit.estimated) {
    if (!block.estimated) continue;
    const std::string name = block.name;
    auto sigma = [&](int k) { return std::sqrt(covariance(column + k, column + k)); };
    if (name == "focal") {
      result->extras.push_back({"fx", file.fx, result->camera.fx, sigma(0) * file.fx});
      result->extras.push_back({"fy", file.fy, result->camera.fy, sigma(0) * file.fy});
    } else if (name == "principal") {
      result->extras.push_back({"cx", file.cx, result->camera.cx, sigma(0)});
      result->extras.push_back({"cy", file.cy, result->camera.cy, sigma(1)});
    } else {
      result->extras.push_back({"target_scale", 1.0, result->target_scale, sigma(0)});
    }
    column += block.size;
  }
}

// The names of the global columns: "leg 1 ax", ..., then the estimated blocks'.
std::vector<std::string> ColumnNames(const PixelFit& fit) {
  std::vector<std::string> names;
  for (int i = 0; i < kNumLegs; ++i)
    for (int k = 0; k < kParamsPerLeg; ++k) names.push_back("leg " + std::to_string(i + 1) + " " + ParameterName(k));
  for (const EstimatedBlock& block : fit.estimated) {
    if (!block.estimated) continue;
    if (std::string(block.name) == "focal") names.push_back("focal");
    if (std::string(block.name) == "principal") names.insert(names.end(), {"cx", "cy"});
    if (std::string(block.name) == "target_scale") names.push_back("target_scale");
  }
  return names;
}

// Pairs with an estimated camera or target quantity whose |correlation| > 0.95.
std::vector<PixelCorrelation> StrongCorrelations(const PixelFit& fit, const MatrixXd& covariance) {
  const std::vector<std::string> names = ColumnNames(fit);
  std::vector<PixelCorrelation> lines;
  for (int a = kNumParams; a < covariance.rows(); ++a) {
    for (int b = 0; b < a; ++b) {
      const double rho = covariance(a, b) / std::sqrt(covariance(a, a) * covariance(b, b));
      if (std::abs(rho) > 0.95) lines.push_back({names[b], names[a], rho});
    }
  }
  return lines;
}

}  // namespace

StatusOr<PixelCalibrationResult> SummarizePixelFit(const PixelCalibrationInput& input, const PixelFit& fit,
                                                   const PixelCalibrationOptions& options) {
  const JointFitInformation information = ReducedInformationAt(fit.problem, Columns(fit));
  if (ScaledConditionInverse(information.reduced) < 1e-12) {
    return Status::Failed(
        "calibration from pixels: the data do not determine every estimated quantity (a singular information "
        "matrix); estimate fewer camera quantities or add poses");
  }
  PixelCalibrationResult result;
  result.variance_factor = information.VarianceFactor();
  const MatrixXd covariance = information.Covariance();
  FillLegs(input, fit, covariance, options, result.variance_factor, &result);
  FillExtras(input, fit, covariance, &result);
  result.strong_correlations = StrongCorrelations(fit, covariance);
  result.corner_residuals = CornerResiduals(fit);
  result.corners = static_cast<int>(result.corner_residuals.size());
  result.reprojection_rms_px = ReprojectionRms(result.corner_residuals);
  return result;
}

}  // namespace hexcal
