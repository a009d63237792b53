#include "vision/intrinsics.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <functional>
#include <limits>
#include <memory>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "core/csv.h"
#include "core/parallel.h"
#include "core/pose.h"
#include "vision/fisheye_init.h"
#include "vision/intrinsics_diagnosis.h"

namespace hexcal {
namespace {

using ImageLoader = std::function<StatusOr<cv::Mat>(int index)>;

struct Detected {
  bool loaded = false;
  std::string error;
  cv::Size size;
  BoardObservation observation;
};

// Detects every image (threads workers, one detector each); false if cancelled.
StatusOr<std::vector<Detected>> DetectAll(int count, const ImageLoader& load, const Target& target,
                                          const IntrinsicsOptions& options, std::shared_ptr<const IdealPixelMap> ideal,
                                          const std::vector<bool>& wanted, const JobHooks& hooks) {
  const int workers = ParallelWorkers(count, options.threads);
  StatusOr<std::vector<std::unique_ptr<TagDetector>>> created =
      CreateWorkerDetectors(ForTarget(options.detector, target), ideal, workers);
  if (!created.ok()) return created.status();
  std::vector<std::unique_ptr<TagDetector>> detectors = std::move(*created);
  std::vector<Detected> detected(static_cast<size_t>(count));
  const bool finished = ParallelFor(
      count, options.threads,
      [&](int index, int worker) {
        Detected& d = detected[static_cast<size_t>(index)];
        if (!wanted.empty() && !wanted[static_cast<size_t>(index)]) return;
        StatusOr<cv::Mat> image = load(index);
        if (!image.ok()) {
          d.error = image.status().message();
          return;
        }
        d.loaded = true;
        d.size = image->size();
        d.observation = MatchToTarget(target, detectors[static_cast<size_t>(worker)]->Detect(*image));
      },
      hooks);
  if (!finished) return Status::Cancelled("intrinsics: cancelled during detection");
  return detected;
}

struct Calibration {
  Camera camera;
  std::vector<double> std_dev;  // empty: not estimated
  double rms = 0;
  std::vector<double> view_rms;  // per used view, in order
  std::vector<CornerResidual> corners;  // `image`: the index of the view in the list calibrated
};

// The fit's RMS figures and every corner's residual from the camera and the
// views' poses (Camera::Project), so that every model's figures mean the same.
void ReprojectionRms(const std::vector<const BoardObservation*>& views, const std::vector<cv::Mat>& rvecs,
                     const std::vector<cv::Mat>& tvecs, Calibration& result) {
  double total = 0;
  size_t corners = 0;
  for (size_t v = 0; v < views.size(); ++v) {
    cv::Mat r, t, rotation;
    rvecs[v].reshape(1, 3).convertTo(r, CV_64F);
    tvecs[v].reshape(1, 3).convertTo(t, CV_64F);
    cv::Rodrigues(r, rotation);
    Pose camera_from_target;
    for (int i = 0; i < 3; ++i) {
      camera_from_target.position[i] = t.at<double>(i);
      for (int j = 0; j < 3; ++j) camera_from_target.rotation(i, j) = rotation.at<double>(i, j);
    }
    double sum = 0;
    for (size_t i = 0; i < views[v]->image_points.size(); ++i) {
      const Eigen::Vector3d p_in_camera = camera_from_target * views[v]->target_points[i];
      const Eigen::Vector2d residual = result.camera.Project(p_in_camera) - views[v]->image_points[i];
      sum += residual.squaredNorm();
      result.corners.push_back({static_cast<int>(v), views[v]->tag_ids[i / 4], static_cast<int>(i % 4),
                                views[v]->image_points[i], residual});
    }
    const size_t n = views[v]->image_points.size();
    result.view_rms.push_back(std::sqrt(sum / static_cast<double>(std::max<size_t>(1, n))));
    total += sum;
    corners += n;
  }
  result.rms = std::sqrt(total / static_cast<double>(std::max<size_t>(1, corners)));
}

// cv::fisheye::calibrate: every point as double (CV_64FC3 / CV_64FC2).
double CalibrateFisheye(const std::vector<const BoardObservation*>& views, cv::Size size, cv::Mat& k, cv::Mat& d,
                        std::vector<cv::Mat>& rvecs, std::vector<cv::Mat>& tvecs) {
  std::vector<std::vector<cv::Point3d>> object(views.size());
  std::vector<std::vector<cv::Point2d>> image(views.size());
  for (size_t v = 0; v < views.size(); ++v) {
    for (size_t i = 0; i < views[v]->image_points.size(); ++i) {
      const Eigen::Vector3d& p = views[v]->target_points[i];
      object[v].emplace_back(p.x(), p.y(), p.z());
      image[v].emplace_back(views[v]->image_points[i].x(), views[v]->image_points[i].y());
    }
  }
  int flags = cv::fisheye::CALIB_RECOMPUTE_EXTRINSIC | cv::fisheye::CALIB_FIX_SKEW;
  // OpenCV's own start (f = side / π) fails for lenses wider than that:
  // start from the focal length the views agree on (vision/fisheye_init.h).
  if (std::optional<FisheyeStart> start = EquidistantStart(views, size)) {
    k = cv::Mat(start->CameraMatrix());
    d = cv::Mat::zeros(4, 1, CV_64F);
    flags |= cv::fisheye::CALIB_USE_INTRINSIC_GUESS;
  }
  return cv::fisheye::calibrate(object, image, size, k, d, rvecs, tvecs, flags,
                                cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 200, 1e-12));
}

// cv::calibrateCamera, with the rational model's flag when asked; the
// standard deviations of fx fy cx cy and the model's coefficients.
void CalibrateRadTan(const std::vector<const BoardObservation*>& views, cv::Size size, CameraModel model, cv::Mat& k,
                     cv::Mat& d, std::vector<cv::Mat>& rvecs, std::vector<cv::Mat>& tvecs, cv::Mat& std_intrinsics) {
  std::vector<std::vector<cv::Point3f>> object(views.size());
  std::vector<std::vector<cv::Point2f>> image(views.size());
  for (size_t v = 0; v < views.size(); ++v) {
    for (size_t i = 0; i < views[v]->image_points.size(); ++i) {
      const Eigen::Vector3d& p = views[v]->target_points[i];
      object[v].emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
      image[v].emplace_back(static_cast<float>(views[v]->image_points[i].x()),
                            static_cast<float>(views[v]->image_points[i].y()));
    }
  }
  cv::Mat std_extrinsics, per_view;
  const int flags = model == CameraModel::kRational ? cv::CALIB_RATIONAL_MODEL : 0;
  cv::calibrateCamera(object, image, size, k, d, rvecs, tvecs, std_intrinsics, std_extrinsics, per_view, flags,
                      cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 200, 1e-12));
}

StatusOr<Calibration> Calibrate(const std::vector<const BoardObservation*>& views, cv::Size size, CameraModel model) {
  cv::Mat k, d, std_intrinsics;
  std::vector<cv::Mat> rvecs, tvecs;
  Calibration result;
  try {
    if (model == CameraModel::kPinholeEqui) {
      CalibrateFisheye(views, size, k, d, rvecs, tvecs);
    } else {
      CalibrateRadTan(views, size, model, k, d, rvecs, tvecs, std_intrinsics);
    }
  } catch (const cv::Exception& e) {
    return Status::Failed(std::string("calibration failed: ") + e.msg);
  }
  result.camera.width = size.width;
  result.camera.height = size.height;
  result.camera.model = model;
  result.camera.fx = k.at<double>(0, 0);
  result.camera.fy = k.at<double>(1, 1);
  result.camera.cx = k.at<double>(0, 2);
  result.camera.cy = k.at<double>(1, 2);
  const int coefficients = result.camera.NumCoefficients();
  for (int i = 0; i < coefficients; ++i) result.camera.distortion[static_cast<size_t>(i)] = d.at<double>(i);
  if (!std_intrinsics.empty()) {
    for (int i = 0; i < 4 + coefficients; ++i) result.std_dev.push_back(std_intrinsics.at<double>(i));
  }
  if (Status s = result.camera.Validate(); !s.ok())
    return Status::Failed("calibration gave an invalid camera: " + s.message());
  if (rvecs.size() != views.size() || tvecs.size() != views.size())
    return Status::Failed("calibration failed: no pose for every view");
  ReprojectionRms(views, rvecs, tvecs, result);
  if (!std::isfinite(result.rms)) return Status::Failed("calibration failed: the reprojection error is not finite");
  return result;
}

// Calibrates the views marked used, dropping outliers one at a time.
StatusOr<Calibration> CalibrateWithOutliers(std::vector<CalibrationView>& views, const std::vector<Detected>& detected,
                                            cv::Size size, const IntrinsicsOptions& options) {
  while (true) {
    std::vector<const BoardObservation*> used;
    std::vector<size_t> index;
    for (size_t i = 0; i < views.size(); ++i) {
      if (!views[i].used) continue;
      used.push_back(&detected[i].observation);
      index.push_back(i);
    }
    StatusOr<Calibration> calibration = Calibrate(used, size, options.model);
    if (!calibration.ok()) return calibration;
    std::vector<double> sorted = calibration->view_rms;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double median = sorted[sorted.size() / 2];
    // The floor spares sharp views a few hundredths of a pixel over a tiny
    // median; a view ten times worse than most is bad whatever its RMS.
    const double limit =
        options.keep_outliers
            ? std::numeric_limits<double>::infinity()
            : std::min(std::max(options.outlier_factor * median, options.outlier_min_rms_px),
                       options.far_outlier_factor * median);
    const auto worst = std::max_element(calibration->view_rms.begin(), calibration->view_rms.end());
    for (size_t u = 0; u < index.size(); ++u) views[index[u]].rms_px = calibration->view_rms[u];
    if (*worst <= limit || static_cast<int>(used.size()) <= options.min_views) {
      for (CornerResidual& corner : calibration->corners) corner.image = static_cast<int>(index[corner.image]);
      return calibration;
    }
    CalibrationView& outlier = views[index[static_cast<size_t>(worst - calibration->view_rms.begin())]];
    outlier.used = false;
    outlier.reason = "outlier: RMS " + FormatSignificant(*worst) + " px > " + FormatSignificant(limit) + " px";
  }
}

// Calibrates alternate halves of the used views apart and compares them.
CrossValidation CrossValidate(const std::vector<CalibrationView>& views, const std::vector<Detected>& detected,
                              cv::Size size, const Camera& full, CameraModel model) {
  std::vector<const BoardObservation*> halves[2];
  for (size_t i = 0; i < views.size(); ++i) {
    if (views[i].used) halves[(halves[0].size() + halves[1].size()) % 2].push_back(&detected[i].observation);
  }
  if (halves[1].size() < 3) return {};
  const StatusOr<Calibration> a = Calibrate(halves[0], size, model), b = Calibrate(halves[1], size, model);
  if (!a.ok() || !b.ok()) return {};
  CrossValidation cross = CompareHalves(full, a->camera, a->std_dev, b->camera, b->std_dev);
  cross.views_a = static_cast<int>(halves[0].size());
  cross.views_b = static_cast<int>(halves[1].size());
  return cross;
}

StatusOr<IntrinsicsResult> Run(int count, const std::vector<std::string>& names, const ImageLoader& load,
                               const Target& target, const IntrinsicsOptions& options, const JobHooks& hooks) {
  std::string error;
  if (!options.IsValid(&error)) return Status::BadInput("intrinsics options: " + error);
  if (count == 0) return Status::BadInput("no images");
  const int passes = 1 + options.refinement_passes;
  // Detection pass `pass` of `passes` as one count over every pass.
  auto stage_hooks = [&](int pass) -> JobHooks {
    if (!hooks.progress) return {nullptr, hooks.cancel};
    return {[&hooks, pass, count, passes](int done, int) { hooks.progress(pass * count + done, passes * count); },
            hooks.cancel};
  };
  StatusOr<std::vector<Detected>> detected = DetectAll(count, load, target, options, nullptr, {}, stage_hooks(0));
  if (!detected.ok()) return detected.status();

  IntrinsicsResult result;
  cv::Size size;
  std::string size_source;
  for (int i = 0; i < count; ++i) {
    const Detected& d = (*detected)[static_cast<size_t>(i)];
    CalibrationView view;
    view.file = names[static_cast<size_t>(i)];
    if (!d.loaded) {
      view.reason = d.error;
    } else if (size.empty()) {
      size = d.size;
      size_source = view.file;
    } else if (d.size != size) {
      return Status::BadInput("images have different sizes: " + size_source + " is " + std::to_string(size.width) +
                              " x " + std::to_string(size.height) + ", " + view.file + " is " +
                              std::to_string(d.size.width) + " x " + std::to_string(d.size.height));
    }
    view.tags = d.observation.NumTags();
    view.used = d.loaded && view.tags >= options.min_tags_per_view;
    if (d.loaded && !view.used) {
      view.reason =
          std::to_string(view.tags) + " target tags, " + std::to_string(options.min_tags_per_view) + " needed";
    }
    result.views.push_back(view);
  }
  const int usable = static_cast<int>(
      std::count_if(result.views.begin(), result.views.end(), [](const CalibrationView& v) { return v.used; }));
  const auto loaded = std::find_if(detected->begin(), detected->end(), [](const Detected& d) { return d.loaded; });
  if (usable == 0 && loaded != detected->end()) {
    // Bad input, as measure and calibrate --session have it: the wrong
    // images, or a target file that does not describe the printed board.
    const CalibrationView& first = result.views[static_cast<size_t>(loaded - detected->begin())];
    return Status::BadInput("no image shows the target: 0 of " + std::to_string(count) + " images show at least " +
                            std::to_string(options.min_tags_per_view) + " target tags (" + first.file + ": " +
                            std::to_string(first.tags) + " tags" +
                            "); check that these are images of the board and that --target describes it as printed "
                            "(hexcal detect --images IMAGE says what an image holds)");
  }
  if (usable < options.min_views) {
    return Status::Failed("too few usable views: " + std::to_string(usable) + " of " + std::to_string(count) +
                          " images show at least " + std::to_string(options.min_tags_per_view) +
                          " target tags; at least " + std::to_string(options.min_views) + " are needed");
  }
  StatusOr<Calibration> calibration = CalibrateWithOutliers(result.views, *detected, size, options);
  if (!calibration.ok()) return calibration.status();
  for (int pass = 1; pass <= options.refinement_passes; ++pass) {
    // Straight edges are straight in the undistorted image only: detect again
    // with the distortion just estimated, and calibrate again.
    std::vector<bool> wanted;
    for (const CalibrationView& view : result.views)
      wanted.push_back(view.used || view.tags >= options.min_tags_per_view);
    auto ideal = std::make_shared<const IdealPixelMap>(calibration->camera);
    detected = DetectAll(count, load, target, options, ideal, wanted, stage_hooks(pass));
    if (!detected.ok()) return detected.status();
    for (size_t i = 0; i < result.views.size(); ++i) {
      CalibrationView& view = result.views[i];
      if (!wanted[i]) continue;
      view.tags = (*detected)[i].observation.NumTags();
      view.used = view.tags >= options.min_tags_per_view;
      view.reason = view.used ? "" : std::to_string(view.tags) + " target tags after re-detection";
    }
    calibration = CalibrateWithOutliers(result.views, *detected, size, options);
    if (!calibration.ok()) return calibration.status();
  }
  result.camera = calibration->camera;
  result.std_dev = calibration->std_dev;
  result.rms_px = calibration->rms;
  result.corner_residuals = std::move(calibration->corners);
  result.cross_validation = CrossValidate(result.views, *detected, size, result.camera, options.model);
  for (size_t i = 0; i < result.views.size(); ++i) {
    CalibrationView& view = result.views[i];
    if (!view.used) view.rms_px = 0;
    result.used_views += view.used;
    view.corners = (*detected)[i].observation.image_points;
  }
  return result;
}

}  // namespace

bool IntrinsicsOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!detector.IsValid(error)) return false;
  if (threads < 0 || threads > 64) return fail("threads: must be in 0..64 (0: every core)");
  if (min_tags_per_view < 1) return fail("min_tags_per_view: must be at least 1");
  if (min_views < 3) return fail("min_views: must be at least 3");
  if (!(outlier_factor > 1)) return fail("outlier_factor: must be greater than 1");
  if (!(outlier_min_rms_px >= 0)) return fail("outlier_min_rms_px: must be >= 0");
  if (!(far_outlier_factor >= outlier_factor)) return fail("far_outlier_factor: must be at least outlier_factor");
  if (refinement_passes < 0 || refinement_passes > 5) return fail("refinement_passes: must be in 0..5");
  if (!(max_rms_px > 0)) return fail("max_rms_px: must be > 0");
  return true;
}

StatusOr<IntrinsicsResult> CalibrateIntrinsics(const std::vector<std::string>& files, const Target& target,
                                               const IntrinsicsOptions& options, const JobHooks& hooks) {
  return Run(
      static_cast<int>(files.size()), files,
      [&files](int index) { return LoadGrayImage(files[static_cast<size_t>(index)]); }, target, options, hooks);
}

StatusOr<IntrinsicsResult> CalibrateIntrinsicsFromImages(const std::vector<cv::Mat>& images,
                                                         const std::vector<std::string>& names, const Target& target,
                                                         const IntrinsicsOptions& options, const JobHooks& hooks) {
  return Run(
      static_cast<int>(images.size()), names,
      [&images](int index) -> StatusOr<cv::Mat> { return images[static_cast<size_t>(index)]; }, target, options, hooks);
}

CameraFileExtras ExtrasOf(const IntrinsicsResult& result) {
  CameraFileExtras extras;
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char stamp[32];
  std::strftime(stamp, sizeof(stamp), "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&now));
  extras.calibration_time = stamp;
  extras.views = result.used_views;
  extras.rms_px = result.rms_px;
  extras.std_dev = result.std_dev;
  for (const CalibrationView& view : result.views) {
    if (view.used) extras.per_view_rms_px.push_back(view.rms_px);
  }
  extras.comment = "hexcal intrinsics (" + std::string(CameraModelName(result.camera.model)) +
                   "): " + std::to_string(result.used_views) + " of " + std::to_string(result.views.size()) +
                   " images used, RMS " + FormatSignificant(result.rms_px) + " px";
  if (result.std_dev.empty())
    extras.comment += "\nno standard deviations: the fisheye calibration does not estimate them";
  return extras;
}

}  // namespace hexcal
