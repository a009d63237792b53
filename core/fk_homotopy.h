// Forward kinematics with every assembly mode: all real poses of a 6-6
// platform for given leg readings.
//
// Method: parameter homotopy on the Study-parameter system of study_system.h.
// A generic complex instance of the problem (random attachment points and leg
// lengths) is solved once, by a total-degree homotopy over 2^7 = 128 paths,
// for its 40 solutions (the generic number: Husty 1996, Wampler 1996). Any
// real instance is then reached by moving the parameters along a straight
// line from the generic instance to the real one and tracking the 40 paths:
// since the start is generic and complex, the line misses the discriminant
// with probability one, so every isolated solution of the target is the end
// of a path (Morgan & Sommese 1989). Real solutions are polished by Newton on
// the leg equations. Unlike a multistart Newton, nothing can be missed except
// singular (double) solutions at a parallel singularity.
//
// At a parallel singularity two modes merge into a double root, and the paths
// to it stop short of s = 0 (or end with a small imaginary part). An end-game
// recovers the real pose from each such path end: damped Gauss-Newton on the
// real leg equations from the real part of its last point. Such a pose is
// flagged (`at_singularity`): the readings do not determine the pose's motion
// there.
//
//   StatusOr<FkAllResult> modes = ForwardKinematicsAll(robot, readings);
//   for (const Pose& pose : modes->poses) ...
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "core/inverse_kinematics.h"
#include "core/status.h"
#include "core/study_system.h"

namespace hexcal {

struct FkAllOptions {
  // A solution is real when the imaginary parts of R and t/scale are below this.
  double imaginary_tolerance = 1e-6;
  // End-game: a failed path end, or a solution whose imaginary parts are below
  // this, is polished from its real part; kept when the legs then match.
  double endgame_imaginary_tolerance = 1e-2;
  // A real mode whose Jacobian condition ratio (forward_kinematics.h) is below
  // this is reported as at a singularity.
  double singular_condition_ratio = 1e-6;
};

struct FkAllResult {
  std::vector<Pose> poses;           // every real assembly mode, polished, sorted by z descending
  std::vector<bool> at_singularity;  // per pose: at a parallel singularity (a double root)
  int complex_solutions = 0;         // non-real finite solutions (conjugate pairs counted twice)
  int failed_paths = 0;              // paths that ended singular or diverged (before the end-game)
  int endgame_poses = 0;             // real poses recovered by the end-game from failed or nearly real path ends
  int SingularCount() const { return static_cast<int>(std::count(at_singularity.begin(), at_singularity.end(), true)); }
  int tracked_paths = 0;
};

StatusOr<FkAllResult> ForwardKinematicsAll(const Robot& robot, const LegReadings& readings,
                                           const FkAllOptions& options = {});

// Forward kinematics of many readings of one robot (the boundary candidates'
// 64 min/max combinations). The robot's own generic instance, its attachment
// points with random complex leg lengths (the hub), is solved once from the
// generic start system; every reading is then reached from it by a parameter
// homotopy in the leg lengths alone. The hub is generic in that family, so by
// the same theorem (Morgan & Sommese 1989) its finite non-spurious solutions
// reach every isolated solution of any reading, and the paths are short and
// fewer than 40: those that end at infinity or on Δ = 0 for this robot are
// gone. Each Solve gives the modes ForwardKinematicsAll gives
// (fk_homotopy_test checks it on every combination).
class FkFamily {
 public:
  // Solves the hub (about the cost of one ForwardKinematicsAll).
  static StatusOr<FkFamily> ForRobot(const Robot& robot, const FkAllOptions& options = {});
  // Every real mode at `readings`, on the calling thread; thread-safe.
  StatusOr<FkAllResult> Solve(const LegReadings& readings) const;
  int hub_solutions() const { return static_cast<int>(solutions_.size()); }

 private:
  Robot robot_;
  FkAllOptions options_;
  double scale_ = 1;  // lengths are divided by the longest leg at full stroke
  StudyParameters hub_;
  CVector8 chart_;
  std::vector<CVector8> solutions_;
};

// The generic complex instance and its 40 solutions. Its parameters come from
// a fixed seed; its solutions are shipped (core/fk_start_solutions.inc), each
// checked by Newton on first use, so a process pays for no 128-path solve
// (docs/kinematics.md); should any check fail, they are solved afresh.
struct StartSystem {
  StudyParameters params;
  CVector8 chart;
  std::vector<CVector8> solutions;
  int total_degree_runs = 0;        // runs of the 128-path homotopy it took (0: shipped)
  bool from_shipped_data = false;
};
constexpr uint64_t kStartSystemSeed = 20050601;  // fixed: the start system is part of the method
const StartSystem& GenericStartSystem();
// Solves a random generic instance from scratch (deterministic in seed).
StartSystem SolveGenericInstance(uint64_t seed);
// The shipped solutions checked against the instance of kStartSystemSeed;
// empty solutions when a check fails.
StartSystem ShippedStartSystem();
// `solutions` as the text of core/fk_start_solutions.inc.
std::string FormatStartSolutions(const std::vector<CVector8>& solutions);

}  // namespace hexcal
