#include "core/fk_homotopy.h"

#include <algorithm>
#include <mutex>
#include <random>
#include <sstream>
#include <thread>

#include "core/forward_kinematics.h"
#include "core/path_tracker.h"

namespace hexcal {
namespace {

constexpr int kGenericSolutionCount = 40;
constexpr uint64_t kStartSystemSeed = 20050601;  // fixed: the start system is part of the method

std::array<LegCoefficients, 6> CoefficientsAt(const StudyParameters& p) {
  std::array<LegCoefficients, 6> c;
  for (int i = 0; i < 6; ++i) c[i] = CoefficientsOf(p.a[i], p.b[i], p.d2[i]);
  return c;
}

// H(z, s) = (1 - s) F(z) + s γ G(z), with G_k = z_{k+1}² - z_0² (k = 0..6) and
// the chart equation shared. G has the 2^7 start solutions z_{k+1} = ±z_0.
class TotalDegreeHomotopy : public Homotopy {
 public:
  TotalDegreeHomotopy(const StudyParameters& target, const CVector8& chart, Complex gamma)
      : target_(CoefficientsAt(target)), chart_(chart), gamma_(gamma) {}

  void Evaluate(const CVector8& z, double s, CVector8* h, CMatrix8* hz, CVector8* hs) const override {
    CVector8 f;
    CMatrix8 fz;
    EvaluateStudySystem(target_, chart_, z, &f, hz ? &fz : nullptr);
    CVector8 g = CVector8::Zero();
    CMatrix8 gz = CMatrix8::Zero();
    for (int k = 0; k < 7; ++k) {
      g[k] = z[k + 1] * z[k + 1] - z[0] * z[0];
      gz(k, k + 1) = 2.0 * z[k + 1];
      gz(k, 0) = -2.0 * z[0];
    }
    *h = (1 - s) * f + s * gamma_ * g;
    (*h)[7] = f[7];
    if (hz) {
      *hz = (1 - s) * fz + s * gamma_ * gz;
      hz->row(7) = fz.row(7);
    }
    if (hs) {
      *hs = gamma_ * g - f;
      (*hs)[7] = 0.0;
    }
  }

  std::vector<CVector8> StartSolutions() const {
    std::vector<CVector8> starts;
    for (int signs = 0; signs < 128; ++signs) {
      CVector8 sigma;
      sigma[0] = 1.0;
      for (int k = 0; k < 7; ++k) sigma[k + 1] = (signs >> k) & 1 ? -1.0 : 1.0;
      starts.push_back(sigma / Complex(chart_.transpose() * sigma));
    }
    return starts;
  }

 private:
  std::array<LegCoefficients, 6> target_;
  CVector8 chart_;
  Complex gamma_;
};

// F(z; p(s)) with p(s) = target + s (start - target).
class ParameterHomotopy : public Homotopy {
 public:
  ParameterHomotopy(const StudyParameters& start, const StudyParameters& target, const CVector8& chart)
      : start_(start), target_(target), chart_(chart) {}

  void Evaluate(const CVector8& z, double s, CVector8* h, CMatrix8* hz, CVector8* hs) const override {
    std::array<LegCoefficients, 6> c;
    for (int i = 0; i < 6; ++i) {
      const CVector3 a = target_.a[i] + s * (start_.a[i] - target_.a[i]);
      const CVector3 b = target_.b[i] + s * (start_.b[i] - target_.b[i]);
      const Complex d2 = target_.d2[i] + s * (start_.d2[i] - target_.d2[i]);
      c[i] = CoefficientsOf(a, b, d2);
      if (hs) {
        const LegCoefficients dc = CoefficientDerivative(a, b, start_.a[i] - target_.a[i],
                                                         start_.b[i] - target_.b[i], start_.d2[i] - target_.d2[i]);
        (*hs)[i] = LegLinearPart(dc, z);  // the 4 g·g term does not depend on p
      }
    }
    EvaluateStudySystem(c, chart_, z, h, hz);
    if (hs) (*hs)[6] = (*hs)[7] = 0.0;
  }

 private:
  StudyParameters start_, target_;
  CVector8 chart_;
};

Complex Delta(const CVector8& z) { return Complex(z.head<4>().transpose() * z.head<4>()); }

bool IsSpurious(const CVector8& z) { return std::abs(Delta(z)) < 1e-8 * z.head<4>().squaredNorm(); }

bool ContainsNear(const std::vector<CVector8>& list, const CVector8& z) {
  for (const CVector8& other : list) {
    if ((other - z).norm() < 1e-6 * (1 + z.norm())) return true;
  }
  return false;
}

Complex RandomComplex(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  const double re = u(rng);
  return Complex(re, u(rng));
}

}  // namespace

StartSystem SolveGenericInstance(uint64_t seed) {
  std::mt19937_64 rng(seed);
  StartSystem system;
  for (int i = 0; i < 6; ++i) {
    for (int k = 0; k < 3; ++k) system.params.a[i][k] = RandomComplex(rng);
    for (int k = 0; k < 3; ++k) system.params.b[i][k] = RandomComplex(rng);
    system.params.d2[i] = RandomComplex(rng);
  }
  for (int k = 0; k < 8; ++k) system.chart[k] = RandomComplex(rng);

  TrackerOptions options;
  options.min_step = 1e-9;
  for (int run = 0; run < 6 && static_cast<int>(system.solutions.size()) < kGenericSolutionCount; ++run) {
    ++system.total_degree_runs;
    const Complex gamma = std::polar(1.0, std::uniform_real_distribution<double>(0, 2 * kPi)(rng));
    const TotalDegreeHomotopy homotopy(system.params, system.chart, gamma);
    for (const CVector8& start : homotopy.StartSolutions()) {
      PathEnd end = TrackPath(homotopy, start, options);
      if (!end.reached_end) continue;
      if (!RefineAt(homotopy, 0.0, &end.z, 8, 1e-13)) continue;
      if (IsSpurious(end.z) || ContainsNear(system.solutions, end.z)) continue;
      system.solutions.push_back(end.z);
    }
  }
  return system;
}

const StartSystem& GenericStartSystem() {
  static const StartSystem system = SolveGenericInstance(kStartSystemSeed);
  return system;
}

StatusOr<FkAllResult> ForwardKinematicsAll(const Robot& robot, const LegReadings& readings,
                                           const FkAllOptions& options) {
  const StartSystem& start = GenericStartSystem();
  if (static_cast<int>(start.solutions.size()) != kGenericSolutionCount) {
    std::ostringstream message;
    message << "forward kinematics: the generic start system has " << start.solutions.size()
            << " solutions instead of " << kGenericSolutionCount;
    return Status::Error(message.str());
  }
  // Work in units of the longest leg so the target looks like the unit-size start.
  double scale = 0;
  for (int i = 0; i < kNumLegs; ++i) {
    const double length = readings[i] + robot.legs[i].offset;
    if (!std::isfinite(length) || length <= 0) {
      return Status::Error("forward kinematics: leg " + std::to_string(i + 1) +
                           " has a non-positive or non-finite total length");
    }
    scale = std::max(scale, length);
  }
  StudyParameters target;
  for (int i = 0; i < kNumLegs; ++i) {
    target.a[i] = (robot.legs[i].a_in_base / scale).cast<Complex>();
    target.b[i] = (robot.legs[i].b_in_platform / scale).cast<Complex>();
    const double length = (readings[i] + robot.legs[i].offset) / scale;
    target.d2[i] = length * length;
  }

  const ParameterHomotopy homotopy(start.params, target, start.chart);
  // The 40 paths are independent: track them on every core.
  std::vector<PathEnd> ends(start.solutions.size());
  const int workers = std::max(1u, std::min(std::thread::hardware_concurrency(), 4u));
  auto track_some = [&](int first) {
    for (size_t k = first; k < ends.size(); k += workers) {
      ends[k] = TrackPath(homotopy, start.solutions[k]);
      if (ends[k].reached_end) RefineAt(homotopy, 0.0, &ends[k].z, 4, 1e-14);
    }
  };
  std::vector<std::thread> threads;
  for (int w = 1; w < workers; ++w) threads.emplace_back(track_some, w);
  track_some(0);
  for (std::thread& thread : threads) thread.join();

  FkAllResult result;
  result.tracked_paths = static_cast<int>(ends.size());
  std::vector<Pose> candidates;
  for (const PathEnd& end : ends) {
    if (!end.reached_end || IsSpurious(end.z)) {
      ++result.failed_paths;
      continue;
    }
    CMatrix3 rotation;
    CVector3 translation;
    StudyToComplexPose(end.z, &rotation, &translation);
    const double imaginary = std::max(rotation.imag().cwiseAbs().maxCoeff(), translation.imag().cwiseAbs().maxCoeff());
    if (!(imaginary < options.imaginary_tolerance)) {
      ++result.complex_solutions;
      continue;
    }
    Pose pose;
    pose.rotation = Eigen::Quaterniond(rotation.real()).normalized().toRotationMatrix();
    pose.position = translation.real() * scale;
    candidates.push_back(pose);
  }

  for (const Pose& candidate : candidates) {
    StatusOr<LocalFkResult> polished = ForwardKinematicsLocal(robot, readings, candidate);
    const Pose pose = polished.ok() ? polished->pose : candidate;
    const bool duplicate = std::any_of(result.poses.begin(), result.poses.end(), [&](const Pose& other) {
      return (other.position - pose.position).norm() < 1e-7 * scale &&
             RotationDistance(other.rotation, pose.rotation) < 1e-7;
    });
    if (!duplicate) result.poses.push_back(pose);
  }
  std::sort(result.poses.begin(), result.poses.end(), [](const Pose& p, const Pose& q) {
    if (p.position.z() != q.position.z()) return p.position.z() > q.position.z();
    if (p.position.x() != q.position.x()) return p.position.x() < q.position.x();
    return p.position.y() < q.position.y();
  });
  return result;
}

}  // namespace hexcal
