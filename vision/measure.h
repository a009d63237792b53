// The batch measurement: camera_from_target for every image of a folder.
//
// Each image is read, detected (edge fit in the undistorted image of the
// given camera) and its board pose estimated (board_pose.h), on `threads`
// workers with a detector each. An image that cannot be read, has the wrong
// size or does not show the target gets a status and a message; the batch
// always carries on. Results come back in file order.
//
//   StatusOr<std::vector<std::string>> files = ListImages("shots/");
//   StatusOr<std::vector<ImageMeasurement>> rows = MeasureImages(*files, camera, target, MeasureOptions{});
//   Status written = WriteImageMeasurementsCsv("measurements.csv", *rows);
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "core/status.h"
#include "vision/board_pose.h"
#include "vision/camera.h"
#include "vision/detection.h"
#include "vision/target.h"

namespace hexcal {

struct MeasureOptions {
  DetectorOptions detector;
  BoardPoseOptions pose;
  int threads = 2;  // images in parallel (each detector single-threaded)

  bool IsValid(std::string* error) const;
};

struct ImageMeasurement {
  std::string file;
  BoardPose pose;         // pose.status / pose.message say what happened
  int rejected_tags = 0;  // weak decodes (decision margin, hamming)
  int foreign_tags = 0;   // tags not on the target
};

// The PNG, JPEG and TIFF files of a folder (by extension, any case), sorted by
// name; or the one file given. Error if the folder holds none.
StatusOr<std::vector<std::string>> ListImages(const std::string& folder_or_file);

// Measures one image already in memory.
ImageMeasurement MeasureImage(TagDetector& detector, const cv::Mat& gray, const Camera& camera, const Target& target,
                              const BoardPoseOptions& options);

// Every file; Status::Cancelled if `cancel` was raised.
StatusOr<std::vector<ImageMeasurement>> MeasureImages(
    const std::vector<std::string>& files, const Camera& camera, const Target& target, const MeasureOptions& options,
    const std::function<void(int done, int total)>& progress = nullptr, const std::atomic<bool>* cancel = nullptr);

// The columns of measurements.csv (docs/conventions.md).
std::vector<std::string> ImageMeasurementColumns();
std::vector<std::string> ImageMeasurementRow(const ImageMeasurement& measurement);
// Written atomically (core/atomic_file.h); `file` is written as it is in the measurement.
Status WriteImageMeasurementsCsv(const std::string& path, const std::vector<ImageMeasurement>& measurements);

}  // namespace hexcal
