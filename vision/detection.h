// AprilTag detection with calibration-grade corners, and matching of the
// detected ids to the target.
//
// Quads come from the AprilTag library's segmentation (vision/quad_finder.h)
// of the image as it is, slightly blurred (small tags' thin borders), and of
// the image with its white grown by one pixel (an aprilgrid's corner joints
// opened), and are decoded by hexcal's codebook, which reads one- and
// two-cell borders (vision/tag_decoder.h). The library's own default
// detector runs too, and every tag it finds that those passes missed is kept
// (vision/library_detector.h): never fewer tags than the library. Every
// quad is snapped to the image's edges (vision/quad_snap.h).
// Corners are in OpenCV's pixel-centre convention and are (by default)
// replaced by the sub-pixel edge fit of edge_refine.h. Decodes with a
// decision margin below the threshold, with corrected bits beyond
// max_hamming, or with a corner outside the image (the library extrapolates
// the corners of a tag cut by the border) are rejected and reported.
//
//   StatusOr<std::unique_ptr<TagDetector>> detector = TagDetector::Create(DetectorOptions{});
//   StatusOr<cv::Mat> gray = LoadGrayImage("view.png");
//   Detections found = (*detector)->Detect(*gray);
//   BoardObservation seen = MatchToTarget(target, found);
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/status.h"
#include "vision/camera.h"
#include "vision/image_file.h"
#include "vision/target.h"

namespace hexcal {

struct DetectorOptions {
  std::string family = "tag36h11";
  int border_bits = 1;               // black border cells: 1 (AprilTag), 2 (Kalibr's aprilgrid)
  // AprilTag library worker threads for one image. 1 by default: the worker
  // pool of libapriltag 3.3 (Debian 12) has a race that calls a freed task
  // (a SIGSEGV in a worker thread, fixed upstream in 2024; docs/vision.md).
  int threads = 1;
  double min_decision_margin = 20;  // grey levels; weaker decodes are rejected
  int max_hamming = 0;              // corrected bits accepted, 0..2
  bool refine_edges = true;         // sub-pixel edge fit of each black square
  double quad_sigma = 0;            // AprilTag's blur before segmentation, px (0 = none)
  // Also keep every tag the AprilTag library's default detector finds
  // (vision/library_detector.h; for two-cell borders where hexcal's codebook
  // reads the same tag in its quad): never fewer tags than the library. Off
  // only to measure hexcal's own passes.
  bool library_floor = true;
  // The target's tag ids (ForTarget sets them): when the library's pass
  // alone finds every one of them, accepted, hexcal's own passes are skipped,
  // since they could add no tag of the target (measure's usual image, at
  // about the library's cost; docs/performance.md). Empty: every pass runs.
  std::vector<int> expected_ids;

  bool IsValid(std::string* error) const;
};

struct TagDetection {
  int id = 0;
  std::array<Eigen::Vector2d, 4> corners{
      {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()}};
  // ^ OpenCV pixel convention, AprilTag order
  double decision_margin = 0;
  int hamming = 0;
  bool refined = false;  // corners from the edge fit; else the quad's (vision/quad_finder.h)
  std::string refine_failure;  // why the edge fit was not used ("edge 2: ..."), when it was asked for
  // Covariance of the corners (u0, v0, ..., u3, v3) from the edge fit, px²;
  // zero when not refined.
  Eigen::Matrix<double, 8, 8> covariance = Eigen::Matrix<double, 8, 8>::Zero();
};

struct RejectedTag {
  int id = 0;
  double decision_margin = 0;
  int hamming = 0;
  std::string reason;  // "decision margin 12.3 < 20", "2 corrected bits > 0", "a corner is outside the image"
};

struct Detections {
  std::vector<TagDetection> tags;  // accepted, by id
  std::vector<RejectedTag> rejected;
};

// One AprilTag detector; not thread-safe (use one per thread).
class TagDetector {
 public:
  // `ideal`: the camera's IdealPixelMap, shared between detectors; with it the
  // edge fit works in the undistorted image. May be null.
  static StatusOr<std::unique_ptr<TagDetector>> Create(const DetectorOptions& options,
                                                       std::shared_ptr<const IdealPixelMap> ideal = nullptr);
  ~TagDetector();
  TagDetector(const TagDetector&) = delete;
  TagDetector& operator=(const TagDetector&) = delete;

  // `gray`: CV_8UC1.
  Detections Detect(const cv::Mat& gray);
  // The AprilTag library's detection alone, as configured here (benchmarks).
  int DetectWithLibraryOnly(const cv::Mat& gray);

  const DetectorOptions& options() const { return options_; }

 private:
  struct Impl;
  TagDetector(const DetectorOptions& options, std::unique_ptr<Impl> impl);
  DetectorOptions options_;
  std::unique_ptr<Impl> impl_;
};

// `options` with the target's family, border and tag ids (every detector of
// a job that measures a target is made through this).
DetectorOptions ForTarget(DetectorOptions options, const Target& target);

// One detector per worker of a batch job, each single-threaded (the workers
// already use the cores), sharing `ideal`.
StatusOr<std::vector<std::unique_ptr<TagDetector>>> CreateWorkerDetectors(const DetectorOptions& options,
                                                                          std::shared_ptr<const IdealPixelMap> ideal,
                                                                          int workers);

// The accepted tags whose ids are on the target, as corresponding points.
struct BoardObservation {
  std::vector<int> tag_ids;                                     // one per matched tag
  std::vector<Eigen::Vector3d> target_points;                   // 4 per tag, target frame, AprilTag order
  std::vector<Eigen::Vector2d> image_points;                    // 4 per tag, pixels
  std::vector<Eigen::Matrix<double, 8, 8>> corner_covariances;  // 1 per tag; zero when not refined
  int foreign_tags = 0;                                         // accepted tags whose id is not on the target
  int duplicate_tags = 0;  // tags seen more than once in one image (all copies dropped)
  int NumTags() const { return static_cast<int>(tag_ids.size()); }
};
BoardObservation MatchToTarget(const Target& target, const Detections& detections);

}  // namespace hexcal
