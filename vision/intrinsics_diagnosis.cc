#include "vision/intrinsics_diagnosis.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <vector>

#include "core/csv.h"

namespace hexcal {
namespace {

std::string Px(double value) { return FormatSignificant(value) + " px"; }

}  // namespace

Status CheckIntrinsicsFit(const IntrinsicsResult& result, const Target& target, double max_rms_px) {
  if (result.rms_px <= max_rms_px) return Status::Ok();
  std::vector<const CalibrationView*> bad;
  std::vector<double> view_rms;
  for (const CalibrationView& view : result.views) {
    if (!view.used) continue;
    view_rms.push_back(view.rms_px);
    if (view.rms_px > max_rms_px) bad.push_back(&view);
  }
  std::sort(view_rms.begin(), view_rms.end());
  const double median = view_rms.empty() ? 0 : view_rms[view_rms.size() / 2];
  std::ostringstream why;
  why << "reprojection RMS " << Px(result.rms_px) << " is over the " << Px(max_rms_px)
      << " limit (--max-rms); the camera file was not written. ";
  if (2 * bad.size() >= view_rms.size()) {
    why << bad.size() << " of " << view_rms.size() << " views fit badly (median view RMS " << Px(median)
        << "): a systematic error, not a bad image. Check that the target file describes the board ("
        << DescribeTarget(target)
        << "): rows, cols, tag_spacing, first_id (or ids, or tags) and border_bits as printed, tag_size "
        << "in its length_unit; or, for a wide-angle or fisheye lens, the camera model.";
  } else {
    why << "most views fit (median view RMS " << Px(median) << ") but these do not:";
    for (size_t i = 0; i < bad.size() && i < 5; ++i) why << " " << bad[i]->file << " (" << Px(bad[i]->rms_px) << ")";
    if (bad.size() > 5) why << " and " << bad.size() - 5 << " more";
    why << "; check them (motion blur, a bent board, another board in view) and leave them out.";
  }
  return Status::BadInput(why.str());
}

CrossValidation CompareHalves(const Camera& full, const Camera& a, const std::vector<double>& sigma_a,
                              const Camera& b, const std::vector<double>& sigma_b) {
  constexpr int kCols = 16, kRows = 12;
  CrossValidation cross;
  cross.done = true;
  double sum2 = 0;
  int count = 0;
  for (int row = 0; row < kRows; ++row) {
    for (int col = 0; col < kCols; ++col) {
      const Eigen::Vector2d pixel((col + 0.5) * full.width / kCols - 0.5, (row + 0.5) * full.height / kRows - 0.5);
      const std::optional<Eigen::Vector2d> ray = full.Undistort(pixel);
      if (!ray) continue;
      const Eigen::Vector3d p(ray->x(), ray->y(), 1);
      const double d = (a.Project(p) - b.Project(p)).norm();
      if (!std::isfinite(d)) continue;
      sum2 += d * d;
      cross.max_px = std::max(cross.max_px, d);
      ++count;
    }
  }
  cross.rms_px = count > 0 ? std::sqrt(sum2 / count) : 0;
  if (sigma_a.size() >= 4 && sigma_b.size() >= 4) {
    const double values_a[4] = {a.fx, a.fy, a.cx, a.cy}, values_b[4] = {b.fx, b.fy, b.cx, b.cy};
    for (size_t i = 0; i < 4; ++i) {
      const double sigma = std::hypot(sigma_a[i], sigma_b[i]);
      if (!(sigma > 0) || !std::isfinite(sigma)) continue;
      cross.z.push_back(std::abs(values_a[i] - values_b[i]) / sigma);
      cross.max_z = std::max(cross.max_z, cross.z.back());
    }
  }
  return cross;
}

bool CrossValidationGood(const CrossValidation& cross) {
  return cross.done && cross.rms_px <= kCrossHalvesGoodPx && cross.max_z <= kCrossSigmaGood;
}

std::string DescribeCrossValidation(const CrossValidation& cross) {
  if (!cross.done) return "cross-validation: too few views to split";
  std::string text = "cross-validation (" + std::to_string(cross.views_a) + " + " + std::to_string(cross.views_b) +
                     " views): the halves differ by " + Px(cross.rms_px) + " RMS (" + Px(cross.max_px) +
                     " max) over the image";
  if (!cross.z.empty()) text += ", fx fy cx cy at most " + FormatSignificant(cross.max_z) + " sigma apart";
  const std::string threshold = "within " + Px(kCrossHalvesGoodPx) + " RMS" +
                                (cross.z.empty() ? "" : " and " + FormatSignificant(kCrossSigmaGood) + " sigma");
  if (CrossValidationGood(cross)) return text + ": good (" + threshold + ")";
  text += ": poor (good is " + threshold + ")";
  if (cross.rms_px > kCrossHalvesGoodPx) {
    text +=
        "; the views do not determine the camera: add views that fill the image's corners and edges, at "
        "several distances and tilts";
  }
  if (cross.max_z > kCrossSigmaGood) {
    text +=
        "; the sigma are too small for the data: look for motion blur, a bent board, or a lens the model "
        "does not fit (--model)";
  }
  return text;
}

std::string DescribeWorstView(const IntrinsicsResult& result, double factor) {
  std::vector<double> view_rms;
  const CalibrationView* worst = nullptr;
  for (const CalibrationView& view : result.views) {
    if (!view.used) continue;
    view_rms.push_back(view.rms_px);
    if (worst == nullptr || view.rms_px > worst->rms_px) worst = &view;
  }
  if (view_rms.size() < 3) return "";
  std::nth_element(view_rms.begin(), view_rms.begin() + view_rms.size() / 2, view_rms.end());
  const double median = view_rms[view_rms.size() / 2];
  if (!(worst->rms_px > factor * median)) return "";
  return worst->file + " fits " + FormatSignificant(worst->rms_px / median) + "x worse than the median view (RMS " +
         Px(worst->rms_px) + ", median " + Px(median) +
         "): check it (motion blur, a bent board, another board in view) and leave it out if it is bad";
}

}  // namespace hexcal
