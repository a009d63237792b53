#include "ui/session_jobs.h"

#include <filesystem>

#include "vision/measure.h"

namespace hexcal::ui {

Status MeasureImagesInto(const std::vector<std::string>& files, const Camera& camera, const Target& target,
                         const std::string& measurements_csv, const JobContext& context, int* usable) {
  StatusOr<std::vector<ImageMeasurement>> measured = MeasureImages(files, camera, target, MeasureOptions{}, context);
  if (!measured.ok()) return measured.status();
  *usable = 0;
  for (ImageMeasurement& m : *measured) {
    m.file = std::filesystem::path(m.file).filename().string();
    *usable += m.pose.status == PoseStatus::kOk;
  }
  return WriteImageMeasurementsCsv(measurements_csv, *measured);
}

}  // namespace hexcal::ui
