#include "core/fk_homotopy.h"

#include <algorithm>
#include <mutex>
#include <random>
#include <sstream>

#include "core/forward_kinematics.h"
#include "core/parallel.h"
#include "core/path_tracker.h"

namespace hexcal {
namespace {

constexpr int kGenericSolutionCount = 40;

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
    if (h) {
      *h = (1 - s) * f + s * gamma_ * g;
      (*h)[7] = f[7];
    }
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

// Δ = e·e of a solution (study_system.h).
Complex Delta(const CVector8& z) { return Complex(z.head<4>().transpose() * z.head<4>()); }

// F(z; p(s)) with p(s) = target + s (start - target). Along that line each
// leg's coefficients are quadratic in s (D and A = a bᵀ are products of linear
// terms), so they are expanded once: c(s) = c0 + s c1 + s² c2.
class ParameterHomotopy : public Homotopy {
 public:
  ParameterHomotopy(const StudyParameters& start, const StudyParameters& target, const CVector8& chart)
      : chart_(chart) {
    for (int i = 0; i < 6; ++i) {
      const CVector3 &a = target.a[i], &b = target.b[i];
      const CVector3 da = start.a[i] - a, db = start.b[i] - b;
      const Complex dd2 = start.d2[i] - target.d2[i];
      c0_[i] = CoefficientsOf(a, b, target.d2[i]);
      c1_[i] = CoefficientDerivative(a, b, da, db, dd2);
      c2_[i] = {Complex(da.transpose() * da) + Complex(db.transpose() * db), CVector3::Zero(), CVector3::Zero(),
                da * db.transpose()};
      lengths_only_ = lengths_only_ && da.isZero(0) && db.isZero(0);
    }
  }

  void Evaluate(const CVector8& z, double s, CVector8* h, CMatrix8* hz, CVector8* hs) const override {
    std::array<LegCoefficients, 6> c;
    for (int i = 0; i < 6; ++i) {
      c[i] = {c0_[i].d + s * (c1_[i].d + s * c2_[i].d), c0_[i].a + s * c1_[i].a, c0_[i].b + s * c1_[i].b,
              c0_[i].ab + s * (c1_[i].ab + s * c2_[i].ab)};
      if (hs) {
        const LegCoefficients dc = {c1_[i].d + 2 * s * c2_[i].d, c1_[i].a, c1_[i].b, c1_[i].ab + 2 * s * c2_[i].ab};
        // The 4 g·g term does not depend on p; with the lengths alone moving, only D Δ does.
        (*hs)[i] = lengths_only_ ? dc.d * Delta(z) : LegLinearPart(dc, z);
      }
    }
    EvaluateStudySystem(c, chart_, z, h, hz);
    if (hs) (*hs)[6] = (*hs)[7] = 0.0;
  }

 private:
  std::array<LegCoefficients, 6> c0_, c1_, c2_;
  CVector8 chart_;
  bool lengths_only_ = true;  // the attachment points are the same at both ends (FkFamily)
};

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

// A real assembly mode found by ForwardKinematicsAll, before sorting.
struct RealMode {
  Pose pose;
  bool at_singularity = false;
  bool from_endgame = false;
};

// The pose of a path end (Study parameters, lengths divided by `scale`) and the
// largest imaginary part of its rotation and translation.
Pose RealPartPose(const CVector8& z, double scale, double* imaginary) {
  CMatrix3 rotation;
  CVector3 translation;
  StudyToComplexPose(z, &rotation, &translation);
  *imaginary = std::max(rotation.imag().cwiseAbs().maxCoeff(), translation.imag().cwiseAbs().maxCoeff());
  Pose pose;
  pose.rotation = Eigen::Quaterniond(rotation.real()).normalized().toRotationMatrix();
  pose.position = translation.real() * scale;
  return pose;
}

// Polishes `candidate` on the real leg equations and adds it unless it repeats
// a mode. A path end (`endgame`) is kept only if the polish converges; a
// tracked real solution is kept as it is when the polish fails. At a double
// root Newton converges only linearly, so poses at a singularity are compared
// with a looser tolerance.
void AddRealMode(const Robot& robot, const LegReadings& readings, const Pose& candidate, bool endgame, double scale,
                 const FkAllOptions& options, std::vector<RealMode>* modes) {
  LocalFkOptions local;
  local.accept_singular = true;
  StatusOr<LocalFkResult> polished = ForwardKinematicsLocal(robot, readings, candidate, local);
  if (endgame && !polished.ok()) return;
  RealMode mode{polished.ok() ? polished->pose : candidate, false, endgame};
  mode.at_singularity = polished.ok() && polished->condition_ratio < options.singular_condition_ratio;
  for (RealMode& other : *modes) {
    const double tolerance = (other.at_singularity || mode.at_singularity) ? 1e-5 : 1e-7;
    if ((other.pose.position - mode.pose.position).norm() < tolerance * scale &&
        RotationDistance(other.pose.rotation, mode.pose.rotation) < tolerance) {
      other.at_singularity = other.at_singularity || mode.at_singularity;
      return;
    }
  }
  modes->push_back(mode);
}

// Sorts the real modes (tracked ones first when deduplicating, so that an
// end-game pose never replaces a regular solution) by z descending.
FkAllResult CollectRealModes(const Robot& robot, const LegReadings& readings, const std::vector<PathEnd>& ends,
                             double scale, const FkAllOptions& options) {
  FkAllResult result;
  result.tracked_paths = static_cast<int>(ends.size());
  std::vector<Pose> regular, endgame;
  for (const PathEnd& end : ends) {
    if (IsSpurious(end.z)) {
      ++result.failed_paths;
      continue;
    }
    double imaginary = 0;
    const Pose pose = RealPartPose(end.z, scale, &imaginary);
    const bool finite = pose.position.allFinite() && pose.rotation.allFinite();
    if (!end.reached_end) ++result.failed_paths;
    if (end.reached_end && !(imaginary < options.imaginary_tolerance)) ++result.complex_solutions;
    if (end.reached_end && imaginary < options.imaginary_tolerance) {
      regular.push_back(pose);
    } else if (finite && imaginary < options.endgame_imaginary_tolerance) {
      endgame.push_back(pose);
    }
  }
  std::vector<RealMode> modes;
  for (const Pose& pose : regular) AddRealMode(robot, readings, pose, false, scale, options, &modes);
  for (const Pose& pose : endgame) AddRealMode(robot, readings, pose, true, scale, options, &modes);
  std::sort(modes.begin(), modes.end(), [](const RealMode& a, const RealMode& b) {
    const Pose &p = a.pose, &q = b.pose;
    if (p.position.z() != q.position.z()) return p.position.z() > q.position.z();
    if (p.position.x() != q.position.x()) return p.position.x() < q.position.x();
    return p.position.y() < q.position.y();
  });
  for (const RealMode& mode : modes) {
    result.poses.push_back(mode.pose);
    result.at_singularity.push_back(mode.at_singularity);
    result.endgame_poses += mode.from_endgame;
  }
  return result;
}

// The random generic instance of `seed`: attachment points, squared lengths and chart.
StartSystem GenericInstance(std::mt19937_64& rng) {
  StartSystem system;
  for (int i = 0; i < 6; ++i) {
    for (int k = 0; k < 3; ++k) system.params.a[i][k] = RandomComplex(rng);
    for (int k = 0; k < 3; ++k) system.params.b[i][k] = RandomComplex(rng);
    system.params.d2[i] = RandomComplex(rng);
  }
  for (int k = 0; k < 8; ++k) system.chart[k] = RandomComplex(rng);
  return system;
}

// The solutions of the instance of kStartSystemSeed, from SolveGenericInstance
// (FormatStartSolutions), as {re, im} pairs of the 8 Study unknowns.
constexpr double kShippedSolutions[][8][2] = {
#include "core/fk_start_solutions.inc"
};

}  // namespace

StartSystem SolveGenericInstance(uint64_t seed) {
  std::mt19937_64 rng(seed);
  StartSystem system = GenericInstance(rng);
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

StartSystem ShippedStartSystem() {
  std::mt19937_64 rng(kStartSystemSeed);
  StartSystem system = GenericInstance(rng);
  system.from_shipped_data = true;
  // At s = 0 the total-degree homotopy is the instance's own system.
  const TotalDegreeHomotopy instance(system.params, system.chart, 1.0);
  for (const auto& shipped : kShippedSolutions) {
    CVector8 z;
    for (int k = 0; k < 8; ++k) z[k] = Complex(shipped[k][0], shipped[k][1]);
    CVector8 refined = z;
    const bool root = RefineAt(instance, 0.0, &refined, 4, 1e-13) && (refined - z).norm() < 1e-8 * (1 + z.norm());
    if (!root || IsSpurious(refined) || ContainsNear(system.solutions, refined)) {
      system.solutions.clear();
      return system;
    }
    system.solutions.push_back(refined);
  }
  return system;
}

std::string FormatStartSolutions(const std::vector<CVector8>& solutions) {
  std::ostringstream out;
  out.precision(17);
  for (const CVector8& z : solutions) {
    out << "{";
    for (int k = 0; k < 8; ++k) out << (k ? ", " : "") << "{" << z[k].real() << ", " << z[k].imag() << "}";
    out << "},\n";
  }
  return out.str();
}

const StartSystem& GenericStartSystem() {
  static const StartSystem system = [] {
    StartSystem shipped = ShippedStartSystem();
    if (static_cast<int>(shipped.solutions.size()) == kGenericSolutionCount) return shipped;
    return SolveGenericInstance(kStartSystemSeed);
  }();
  return system;
}

namespace {

Status CheckStartSystem(const StartSystem& start) {
  if (static_cast<int>(start.solutions.size()) == kGenericSolutionCount) return Status::Ok();
  std::ostringstream message;
  message << "forward kinematics: the generic start system has " << start.solutions.size() << " solutions instead of "
          << kGenericSolutionCount;
  return Status::Failed(message.str());
}

// The longest total leg length of `readings`: the unit the instance is solved
// in, so that it looks like the unit-size start.
StatusOr<double> LongestLeg(const Robot& robot, const LegReadings& readings) {
  double scale = 0;
  for (int i = 0; i < kNumLegs; ++i) {
    const double length = readings[i] + robot.legs[i].offset;
    if (!std::isfinite(length) || length <= 0) {
      return Status::BadInput("forward kinematics: leg " + std::to_string(i + 1) +
                              " has a non-positive or non-finite total length");
    }
    scale = std::max(scale, length);
  }
  return scale;
}

// The robot's attachment points and the squared total lengths of `readings`, in units of `scale`.
StudyParameters ScaledInstance(const Robot& robot, const LegReadings& readings, double scale) {
  StudyParameters instance;
  for (int i = 0; i < kNumLegs; ++i) {
    instance.a[i] = (robot.legs[i].a_in_base / scale).cast<Complex>();
    instance.b[i] = (robot.legs[i].b_in_platform / scale).cast<Complex>();
    const double length = (readings[i] + robot.legs[i].offset) / scale;
    instance.d2[i] = length * length;
  }
  return instance;
}

// Tracks the solutions of `from` to `to` (same chart) along the parameter
// line, on up to `threads` cores: the paths are independent.
std::vector<PathEnd> TrackSolutions(const StudyParameters& from, const std::vector<CVector8>& solutions,
                                    const CVector8& chart, const StudyParameters& to, int threads,
                                    double initial_step = TrackerOptions().initial_step) {
  const ParameterHomotopy homotopy(from, to, chart);
  // Paths of special robots (planar-planar, symmetric) that end on the spurious
  // set Δ = 0 converge slowly to a singular point; drop them once they are close.
  TrackerOptions tracker;
  tracker.initial_step = initial_step;
  tracker.give_up = [](const CVector8& z, double s) {
    return s < 0.02 && std::abs(Delta(z)) < 1e-8 * z.head<4>().squaredNorm();
  };
  std::vector<PathEnd> ends(solutions.size());
  ParallelFor(static_cast<int>(ends.size()), threads, [&](int k, int) {
    ends[k] = TrackPath(homotopy, solutions[k], tracker);
    if (ends[k].reached_end) RefineAt(homotopy, 0.0, &ends[k].z, 4, 1e-14);
  });
  return ends;
}

}  // namespace

StatusOr<FkAllResult> ForwardKinematicsAll(const Robot& robot, const LegReadings& readings,
                                           const FkAllOptions& options) {
  const StartSystem& start = GenericStartSystem();
  if (Status s = CheckStartSystem(start); !s.ok()) return s;
  StatusOr<double> scale = LongestLeg(robot, readings);
  if (!scale.ok()) return scale.status();
  const StudyParameters target = ScaledInstance(robot, readings, *scale);
  const std::vector<PathEnd> ends =
      TrackSolutions(start.params, start.solutions, start.chart, target, std::min(ResolveThreadCount(0), 4));
  return CollectRealModes(robot, readings, ends, *scale, options);
}

StatusOr<FkFamily> FkFamily::ForRobot(const Robot& robot, const FkAllOptions& options) {
  const StartSystem& start = GenericStartSystem();
  if (Status s = CheckStartSystem(start); !s.ok()) return s;
  LegReadings longest, middle;
  for (int i = 0; i < kNumLegs; ++i) {
    longest[i] = std::max(robot.legs[i].stroke_min, robot.legs[i].stroke_max);
    middle[i] = 0.5 * (robot.legs[i].stroke_min + robot.legs[i].stroke_max);
  }
  StatusOr<double> scale = LongestLeg(robot, longest);
  if (!scale.ok()) return scale.status();
  FkFamily family;
  family.robot_ = robot;
  family.options_ = options;
  family.scale_ = *scale;
  family.chart_ = start.chart;
  // The hub: mid-stroke lengths moved off the reals at random (by 5 %: enough
  // to be generic, close enough that the paths to every reading are short), a generic
  // member of the robot's family (fixed seed: the set of paths is part of the method).
  family.hub_ = ScaledInstance(robot, middle, *scale);
  std::mt19937_64 rng(kStartSystemSeed + 1);
  for (Complex& d2 : family.hub_.d2) d2 *= 1.0 + 0.05 * RandomComplex(rng);
  const std::vector<PathEnd> ends = TrackSolutions(start.params, start.solutions, start.chart, family.hub_,
                                                   std::min(ResolveThreadCount(0), 4));
  for (const PathEnd& end : ends) {
    if (!end.reached_end || !end.z.allFinite() || IsSpurious(end.z)) continue;
    if (ContainsNear(family.solutions_, end.z)) {  // two paths met: the hub is not generic
      return Status::Failed("forward kinematics: the family's generic instance has a double root");
    }
    family.solutions_.push_back(end.z);
  }
  return family;
}

StatusOr<FkAllResult> FkFamily::Solve(const LegReadings& readings) const {
  StatusOr<double> longest = LongestLeg(robot_, readings);  // refuses a non-positive length
  if (!longest.ok()) return longest.status();
  const StudyParameters target = ScaledInstance(robot_, readings, scale_);
  // The hub is near every reading: a first step of a quarter of the path (the
  // step control halves it where the path bends).
  const std::vector<PathEnd> ends = TrackSolutions(hub_, solutions_, chart_, target, 1, 0.25);
  return CollectRealModes(robot_, readings, ends, scale_, options_);
}

}  // namespace hexcal
