#include "ui/session_jobs.h"

#include <filesystem>
#include <set>

#include "core/csv.h"
#include "vision/measure.h"

namespace hexcal::ui {

Status MeasureImagesInto(const std::vector<std::string>& files, const Camera& camera, const Target& target,
                         const std::string& measurements_csv, const JobContext& context, int* usable) {
  StatusOr<std::vector<ImageMeasurement>> measured =
      MeasureImages(files, camera, target, MeasureOptions{}, context.progress, context.cancel);
  if (!measured.ok()) return measured.status();
  *usable = 0;
  for (ImageMeasurement& m : *measured) {
    m.file = std::filesystem::path(m.file).filename().string();
    *usable += m.pose.status == PoseStatus::kOk;
  }
  return WriteImageMeasurementsCsv(measurements_csv, *measured);
}

bool MeasurementsCover(const std::string& measurements_csv, const std::vector<std::string>& files) {
  StatusOr<CsvTable> table = ReadCsv(measurements_csv);
  if (!table.ok() || table->header != ImageMeasurementColumns()) return false;
  std::set<std::string> measured;
  for (const auto& row : table->rows) measured.insert(row[0]);
  for (const std::string& file : files)
    if (!measured.count(std::filesystem::path(file).filename().string())) return false;
  return true;
}

}  // namespace hexcal::ui
