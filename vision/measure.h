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
//   Status written = WriteImageMeasurementsCsv("camera_poses.csv", *rows);
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/job_hooks.h"
#include "core/status.h"
#include "vision/board_pose.h"
#include "vision/camera.h"
#include "vision/detection.h"
#include "vision/target.h"

namespace hexcal {

struct MeasureOptions {
  DetectorOptions detector;
  BoardPoseOptions pose;
  int threads = 2;  // images in parallel (each detector single-threaded), 0..64; 0: every core
  bool keep_observations = false;  // keep each image's corners (ImageMeasurement::observation)

  bool IsValid(std::string* error) const;
};

struct ImageMeasurement {
  std::string file;
  BoardPose pose;         // pose.status / pose.message say what happened
  int rejected_tags = 0;  // weak decodes (decision margin, hamming)
  int foreign_tags = 0;   // tags not on the target
  // The corners matched to the target, with MeasureOptions::keep_observations
  // (the calibration from pixels, pixel_calibration.h).
  std::optional<BoardObservation> observation;
};

// The PNG, JPEG and TIFF files of a folder (by extension, any case), sorted by
// name; or the one file given. Error if the folder holds none.
StatusOr<std::vector<std::string>> ListImages(const std::string& folder_or_file);

// Measures one image already in memory; `keep_observation` keeps its corners.
ImageMeasurement MeasureImage(TagDetector& detector, const cv::Mat& gray, const Camera& camera, const Target& target,
                              const BoardPoseOptions& options, bool keep_observation = false);

// Every file, in the order given; hooks.Progress(done, files) as images
// finish; Status::Cancelled if hooks.cancel was raised.
StatusOr<std::vector<ImageMeasurement>> MeasureImages(const std::vector<std::string>& files, const Camera& camera,
                                                      const Target& target, const MeasureOptions& options,
                                                      const JobHooks& hooks = {});

// The columns of camera_poses.csv (docs/conventions.md): the pose, its σ,
// rms_px, tags, status, message, then the 15 correlations corr_A_B of the
// pose vector (A before B in x, y, z, q1, q2, q3), empty without a pose.
std::vector<std::string> ImageMeasurementColumns();
// The pose covariance back from the σ and correlation columns; nullopt when a
// σ is negative or not finite or a correlation is outside [-1, 1].
std::optional<Matrix6d> CovarianceFromSigmasAndCorrelations(const std::array<double, 6>& sigma,
                                                            const std::array<double, 15>& correlation);
std::vector<std::string> ImageMeasurementRow(const ImageMeasurement& measurement);
// One row of a camera_poses.csv read back: the pose and its covariance when
// the status is ok, and the cells as written (to write the table again).
struct ImageMeasurementRecord {
  std::string file;
  bool ok = false;
  Pose camera_from_target;                 // target unit; when ok
  Matrix6d covariance = Matrix6d::Zero();  // of the pose vector (Euler xyz): target unit², degrees²; when ok
  std::vector<std::string> cells;
};
// Parses a table written by WriteImageMeasurementsCsv; `source` names it in
// errors: other columns ("not the columns hexcal measure writes"), a cell
// that is not a number, a σ or correlation out of range, each with its line.
StatusOr<std::vector<ImageMeasurementRecord>> ParseImageMeasurementsCsv(const std::string& text,
                                                                        const std::string& source);

// Written atomically (core/atomic_file.h); `file` is written as it is in the measurement.
Status WriteImageMeasurementsCsv(const std::string& path, const std::vector<ImageMeasurement>& measurements);

}  // namespace hexcal
