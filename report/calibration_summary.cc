#include "report/calibration_summary.h"

#include <set>
#include <sstream>

#include "core/outlier_screening.h"
#include "core/session.h"
#include "session/camera_frame_diagnosis.h"
#include "session/image_closure.h"
#include "session/pixel_fit_summary.h"

namespace hexcal::workflow {

namespace {

// One warning per screened-out reading (docs/session.md, "Outliers").
std::string OutlierLines(const CalibrationReport& report) {
  std::ostringstream out;
  out.precision(4);
  if (report.screening && !report.screening->screened) {
    out << "note: " << report.calibration_images << " calibration images are too few to screen the readings for "
        << "outliers (" << kMinRowsToScreen << " needed)\n";
  }
  for (const OutlierReading& o : report.outliers) {
    const std::string leg = "leg " + std::to_string(o.leg);
    out << "outlier: " << o.image;
    if (o.legs_line) out << " (legs.csv line " << *o.legs_line << ")";
    out << " " << leg << ": residual " << o.residual << " " << report.length_unit << " = " << o.z << " sigma; ";
    if (o.excluded) {
      out << "excluded from " << leg << "'s fit (--keep-outliers keeps it)\n";
    } else {
      out << "kept in " << leg << "'s fit (--keep-outliers)\n";
    }
  }
  return out.str();
}

// The images holding an excluded outlier were left out of the registration
// (core/registration.h, CalibrateFromCameraPoses).
std::string RegistrationNote(const CalibrationReport& report) {
  std::set<std::string> images;
  for (const OutlierReading& o : report.outliers)
    if (o.excluded) images.insert(o.image);
  if (images.empty()) return "";
  return ", without the " + std::to_string(images.size()) + (images.size() == 1 ? " image" : " images") +
         " holding an outlier";
}

}  // namespace

std::string FormatCalibrationSummary(const CalibrationReport& report) {
  const std::string& unit = report.length_unit;
  const RegistrationSummary& reg = report.registration;
  std::ostringstream out;
  const bool points = report.instrument == Instrument::kPoints;
  out << "session " << report.session << ": " << report.images << (points ? " poses, " : " images, ")
      << report.calibration_images << " for calibration, " << report.held_out_images << " held out, "
      << report.unusable_images << (points ? " whose points do not fit\n" : " without a usable target pose\n")
      << "registration (nominal robot" << RegistrationNote(report) << "): closure RMS " << reg.position_rms << " "
      << unit << ", " << reg.angle_rms_deg << " deg\n"
      << "after calibration: closure RMS " << report.closure_position_rms << " " << unit << ", "
      << report.closure_angle_rms_deg << " deg\n";
  if (report.validation) {
    const ValidationSummary& v = *report.validation;
    out << "held-out validation (position RMS " << unit << ", orientation RMS deg): before " << v.before.position_rms
        << ", " << v.before.orientation_rms << "; after " << v.after.position_rms << ", " << v.after.orientation_rms
        << "\n";
  }
  if (report.from_pixels) out << FormatPixelFitSummary(*report.from_pixels, unit);
  if (report.from_points) out << FormatPointFitSummary(*report.from_points, unit);
  if (report.camera_frame_residuals) out << FormatCameraFrameLine(*report.camera_frame_residuals, unit) << "\n";
  out << OutlierLines(report);
  out << ImageClosureLines(report.closure_by_image, report.closure_position_rms, unit, report.instrument);
  out << "wrote " << report.calibrated_robot << ", " << CalibrationReportPath(report.session) << ", frames in "
      << SessionPaths(report.session).config << "\n";
  return out.str();
}

}  // namespace hexcal::workflow
