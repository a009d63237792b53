// Benchmarks and accuracy studies of the vision layer on rendered 1024 × 768
// images of the default target (simulated 4.2 mm camera). Figures:
// docs/performance.md.
//   build/bench/hexcal_bench_vision                       # everything (~2 min on 2 cores)
//   build/bench/hexcal_bench_vision --benchmark_filter=Throughput
//
// Throughput: the AprilTag library's own detection and hexcal's whole measure
// (read PNG, detect, edge fit, match, pose, covariance) on the same 24 images.
// Accuracy: errors of measured camera_from_target against the rendered truth,
// median and 95th percentile, and the mean normalised error eᵀ Σ⁻¹ e (6 when
// the reported covariance is right); intrinsics from 20 views in σ of their
// reported standard deviations.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "core/parallel.h"
#include "vision/board_pose.h"
#include "vision/intrinsics.h"
#include "vision/library_detector.h"
#include "vision/measure.h"
#include "vision/renderer.h"

namespace hexcal {
namespace {

constexpr int kThroughputImages = 24;

const Camera& Sim() {
  static const Camera camera = SimulatedCamera();
  return camera;
}

// 24 views at 0.3-0.8 m, in memory and as PNG files in a temporary folder.
struct ImageSet {
  std::vector<cv::Mat> images;
  std::vector<std::string> files;
  std::filesystem::path folder;
  ~ImageSet() {
    std::error_code error;
    std::filesystem::remove_all(folder, error);
  }
};

const ImageSet& Images() {
  static const ImageSet* set = [] {
    auto* s = new ImageSet;
    s->folder = std::filesystem::temp_directory_path() / "hexcal_bench_vision";
    std::filesystem::create_directories(s->folder);
    const Renderer renderer(Sim(), DefaultTarget(), RenderOptions{});
    const std::vector<Pose> poses = RandomViewPoses(DefaultTarget(), kThroughputImages, 300, 800, 35, 30, 0.15, 99);
    for (size_t i = 0; i < poses.size(); ++i) {
      s->images.push_back(renderer.Render(poses[i], i).image);
      s->files.push_back((s->folder / ("view_" + std::to_string(i) + ".png")).string());
      cv::imwrite(s->files.back(), s->images.back());
    }
    return s;
  }();
  return *set;
}

double Percentile(std::vector<double> values, double fraction) {
  std::sort(values.begin(), values.end());
  return values[static_cast<size_t>(std::lround(fraction * (values.size() - 1)))];
}

// ---- throughput -------------------------------------------------------------

void BM_ThroughputAprilTagLibrary(benchmark::State& state) {
  const ImageSet& set = Images();
  DetectorOptions options;
  options.threads = static_cast<int>(state.range(0));
  std::unique_ptr<TagDetector> detector = TagDetector::Create(options).value();
  size_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(detector->DetectWithLibraryOnly(set.images[k++ % set.images.size()]));
  state.SetItemsProcessed(state.iterations());
  state.SetLabel("images/s: apriltag_detector_detect, quad_decimate 1, nthreads " + std::to_string(state.range(0)));
}
BENCHMARK(BM_ThroughputAprilTagLibrary)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The library's own default detector (quad_decimate 2), as apriltag_demo runs it.
void BM_ThroughputAprilTagLibraryDefaults(benchmark::State& state) {
  const ImageSet& set = Images();
  std::unique_ptr<LibraryDetector> detector = LibraryDetector::Create("tag36h11").value();
  size_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(detector->Detect(set.images[k++ % set.images.size()]));
  state.SetItemsProcessed(state.iterations());
  state.SetLabel("images/s: apriltag_detector_detect with its defaults (quad_decimate 2), nthreads 1");
}
BENCHMARK(BM_ThroughputAprilTagLibraryDefaults)->Unit(benchmark::kMillisecond)->UseRealTime();

// range(0): 1 = with the library's default detector as the floor (the default), 0 = hexcal's pass alone.
void BM_ThroughputDetectAndEdgeFit(benchmark::State& state) {
  const ImageSet& set = Images();
  DetectorOptions options;
  options.library_floor = state.range(0) != 0;
  std::unique_ptr<TagDetector> detector =
      TagDetector::Create(options, std::make_shared<const IdealPixelMap>(Sim())).value();
  size_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(detector->Detect(set.images[k++ % set.images.size()]));
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(std::string("images/s: quads, decode, edge fit of every tag; library floor ") +
                 (options.library_floor ? "on" : "off"));
}
BENCHMARK(BM_ThroughputDetectAndEdgeFit)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

// The whole batch, files to poses; range(0) workers, each detector single-threaded.
void BM_ThroughputMeasureBatch(benchmark::State& state) {
  const ImageSet& set = Images();
  MeasureOptions options;
  options.threads = static_cast<int>(state.range(0));
  for (auto _ : state) {
    StatusOr<std::vector<ImageMeasurement>> rows = MeasureImages(set.files, Sim(), DefaultTarget(), options);
    benchmark::DoNotOptimize(rows);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(set.files.size()));
  state.SetLabel("images/s: read PNG, detect, edge fit, pose; " + std::to_string(state.range(0)) + " workers");
}
BENCHMARK(BM_ThroughputMeasureBatch)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The library at its best on both cores, against `hexcal measure`'s batch, in
// the same run: the library detects the 24 in-memory images with two workers
// of one single-threaded detector each (the library's own threads scale worse),
// measure reads, detects, edge-fits and poses the 24 PNG files with two
// workers. Five rounds, alternated; the medians and their ratio (measure /
// library, above 1 is faster; docs/performance.md).
double MedianOf(std::vector<double> values) { return Percentile(std::move(values), 0.5); }

template <typename Work>
double SecondsOf(Work work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BM_MeasureAgainstLibrary(benchmark::State& state) {
  const ImageSet& set = Images();
  constexpr int kWorkers = 2, kRounds = 5;
  DetectorOptions single;
  single.threads = 1;
  std::vector<std::unique_ptr<TagDetector>> library;
  for (int w = 0; w < kWorkers; ++w) library.push_back(TagDetector::Create(single).value());
  MeasureOptions options;
  options.threads = kWorkers;
  const double images = static_cast<double>(set.files.size());
  std::vector<std::unique_ptr<LibraryDetector>> library_defaults;
  for (int w = 0; w < kWorkers; ++w) library_defaults.push_back(LibraryDetector::Create("tag36h11").value());
  std::vector<double> library_rate, library_default_rate, measure_rate;
  for (auto _ : state) {
    for (int round = 0; round < kRounds; ++round) {
      library_rate.push_back(images / SecondsOf([&] {
        ParallelFor(static_cast<int>(set.images.size()), kWorkers, [&](int k, int worker) {
          TagDetector& detector = *library[static_cast<size_t>(worker)];
          benchmark::DoNotOptimize(detector.DetectWithLibraryOnly(set.images[static_cast<size_t>(k)]));
        });
      }));
      library_default_rate.push_back(images / SecondsOf([&] {
        ParallelFor(static_cast<int>(set.images.size()), kWorkers, [&](int k, int worker) {
          benchmark::DoNotOptimize(library_defaults[static_cast<size_t>(worker)]->Detect(set.images[static_cast<size_t>(k)]));
        });
      }));
      measure_rate.push_back(images / SecondsOf([&] {
        benchmark::DoNotOptimize(MeasureImages(set.files, Sim(), DefaultTarget(), options));
      }));
    }
  }
  state.counters["library_img_s"] = MedianOf(library_rate);
  state.counters["measure_img_s"] = MedianOf(measure_rate);
  state.counters["ratio"] = MedianOf(measure_rate) / MedianOf(library_rate);
  state.counters["library_default_img_s"] = MedianOf(library_default_rate);
  state.counters["ratio_default"] = MedianOf(measure_rate) / MedianOf(library_default_rate);
  state.SetLabel("measure (PNG files) / library detection (in memory), 2 workers each, medians of 5");
}
BENCHMARK(BM_MeasureAgainstLibrary)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

void BM_Render(benchmark::State& state) {
  const Renderer renderer(Sim(), DefaultTarget(), RenderOptions{});
  const std::vector<Pose> poses = RandomViewPoses(DefaultTarget(), 8, 300, 800, 35, 30, 0.15, 5);
  uint64_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(renderer.Render(poses[k % poses.size()], k));
    ++k;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Render)->Unit(benchmark::kMillisecond);

// ---- accuracy ---------------------------------------------------------------

// range(0): distance in mm; range(1): blur sigma in 1/10 px; range(2): 1 = edge fit, 0 = library corners.
void BM_AccuracyStudy(benchmark::State& state) {
  const double distance = static_cast<double>(state.range(0));
  RenderOptions render;
  render.blur_sigma_px = state.range(1) / 10.0;
  DetectorOptions detector_options;
  detector_options.refine_edges = state.range(2) != 0;
  const Target target = DefaultTarget();
  constexpr int kViews = 40;
  for (auto _ : state) {
    const Renderer renderer(Sim(), target, render);
    std::unique_ptr<TagDetector> detector =
        TagDetector::Create(detector_options, std::make_shared<const IdealPixelMap>(Sim())).value();
    const std::vector<Pose> poses = RandomViewPoses(target, kViews, distance, distance, 30, 30, 0.1, 2026);
    std::vector<double> translation, rotation, nees;
    int within_3_sigma_z = 0;
    for (size_t i = 0; i < poses.size(); ++i) {
      const BoardPose pose = EstimateBoardPose(
          Sim(), MatchToTarget(target, detector->Detect(renderer.Render(poses[i], i).image)), BoardPoseOptions{});
      if (pose.status != PoseStatus::kOk) continue;
      translation.push_back((pose.camera_from_target.position - poses[i].position).norm());
      rotation.push_back(RadToDeg(RotationDistance(pose.camera_from_target.rotation, poses[i].rotation)));
      Eigen::Matrix<double, 6, 1> e;
      e.head<3>() = RotationLog(pose.camera_from_target.rotation * poses[i].rotation.transpose());
      e.tail<3>() = pose.camera_from_target.position - poses[i].position;
      nees.push_back(e.dot(pose.covariance_local.ldlt().solve(e)));
      within_3_sigma_z += std::abs(e[5]) < 3 * std::sqrt(pose.covariance_local(5, 5));
    }
    state.counters["ok"] = static_cast<double>(translation.size());
    state.counters["t_med_mm"] = Percentile(translation, 0.5);
    state.counters["t_p95_mm"] = Percentile(translation, 0.95);
    state.counters["r_med_deg"] = Percentile(rotation, 0.5);
    state.counters["r_p95_deg"] = Percentile(rotation, 0.95);
    double sum = 0;
    for (double v : nees) sum += v;
    state.counters["NEES_mean"] = sum / nees.size();  // χ²₆: mean 6, median 5.35
    state.counters["NEES_med"] = Percentile(nees, 0.5);
    state.counters["z_in_3sigma"] = static_cast<double>(within_3_sigma_z) / nees.size();
  }
}
BENCHMARK(BM_AccuracyStudy)
    ->ArgNames({"mm", "blur10", "fit"})
    ->Args({300, 7, 1})
    ->Args({500, 7, 1})
    ->Args({800, 7, 1})
    ->Args({500, 7, 0})
    ->Args({500, 4, 1})
    ->Args({500, 12, 1})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

// Intrinsics from 20 views, repeated with range(0) seeds: the largest |error| / σ
// over the nine parameters, and the fraction of parameters within 3σ.
void BM_IntrinsicsStudy(benchmark::State& state) {
  const Camera truth = Sim();
  const Target target = DefaultTarget();
  const int seeds = static_cast<int>(state.range(0));
  for (auto _ : state) {
    double worst = 0;
    int within = 0, total = 0;
    for (int seed = 1; seed <= seeds; ++seed) {
      RenderOptions render;
      render.seed = static_cast<uint64_t>(seed);
      const Renderer renderer(truth, target, render);
      std::vector<cv::Mat> images;
      std::vector<std::string> names;
      const std::vector<Pose> poses = RandomViewPoses(target, 20, 300, 600, 45, 30, 0.25, 100 + seed);
      for (size_t i = 0; i < poses.size(); ++i) {
        images.push_back(renderer.Render(poses[i], i).image);
        names.push_back(std::to_string(i));
      }
      StatusOr<IntrinsicsResult> result = CalibrateIntrinsicsFromImages(images, names, target, IntrinsicsOptions{});
      if (!result.ok()) continue;
      const Camera& c = result->camera;
      const std::array<double, 9> error = {c.fx - truth.fx,
                                           c.fy - truth.fy,
                                           c.cx - truth.cx,
                                           c.cy - truth.cy,
                                           c.distortion[0] - truth.distortion[0],
                                           c.distortion[1] - truth.distortion[1],
                                           c.distortion[2] - truth.distortion[2],
                                           c.distortion[3] - truth.distortion[3],
                                           c.distortion[4] - truth.distortion[4]};
      for (size_t i = 0; i < 9; ++i) {
        const double sigmas = std::abs(error[i]) / result->std_dev[i];
        worst = std::max(worst, sigmas);
        within += sigmas < 3;
        ++total;
      }
      state.counters["rms_px"] = result->rms_px;
      state.counters["fx_err_px"] = error[0];
      state.counters["fx_sigma_px"] = result->std_dev[0];
    }
    state.counters["worst_sigmas"] = worst;
    state.counters["within_3sigma"] = static_cast<double>(within) / total;
  }
}
BENCHMARK(BM_IntrinsicsStudy)->Arg(5)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace hexcal

BENCHMARK_MAIN();
