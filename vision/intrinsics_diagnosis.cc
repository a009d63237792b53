#include "vision/intrinsics_diagnosis.h"

#include <algorithm>
#include <locale>
#include <sstream>
#include <vector>

namespace hexcal {
namespace {

std::string Px(double value) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.precision(3);
  out << value << " px";
  return out.str();
}

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
  return Status::Error(why.str());
}

}  // namespace hexcal
