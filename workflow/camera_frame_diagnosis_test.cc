// The session's bias diagnosis: computed on the demo's virtual laboratory
// (demo_scene.h: true robot and frames, camera poses without rendering), the
// causes simulated only when the residual grows with depth, and the line the
// summary prints.
#include "session/camera_frame_diagnosis.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/inverse_kinematics.h"
#include "sim/demo_scene.h"
#include "tests/robot_presets.h"
#include "tests/test_support.h"
#include "workflow/session_calibrate.h"

namespace hexcal::workflow {
namespace {

using ::hexcal::testing::Preset;
using ::hexcal::testing::RandomFeasiblePoses;
using ::hexcal::testing::Uniform;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// The demo's scene (DeltaLab) seen at 40 poses with its noise, by a camera
// whose file's focal length is (1 + focal_error) times the real one
// (SessionBiasModels: the board's corners projected with the real camera, the
// pose solved with the file's). Over 30 seeds of scene, poses and noise, the
// clean sets made no finding and the 0.5 % ones were named a focal length
// error every time (implied 0.507 % on average).
struct SceneInput {
  DemoScene scene;
  CameraCalibrationInput input;
  BiasCauseModels models;
};

SceneInput MakeInput(double focal_error) {
  const Robot nominal = Preset("deltalab-table");
  SceneInput s{MakeDemoScene(nominal, *LoadCamera(kSimulatedCameraName), *LoadTarget(kDefaultTargetName), {}), {}, {}};
  const double robot_per_target = MetresPerUnit(s.scene.target.length_unit) / MetresPerUnit(nominal.length_unit);
  s.models = SessionBiasModels(s.scene.camera, s.scene.target, robot_per_target);
  const Pose camera_from_base = Inverse(s.scene.base_from_camera);
  std::vector<Pose> seen;
  for (const Vector6d& v : RandomFeasiblePoses(nominal, 40, 5)) {
    const Pose base_from_platform = s.scene.truth.PoseFromVector(v);
    seen.push_back(Compose(Compose(camera_from_base, base_from_platform), s.scene.platform_from_target));
    LegReadings readings = InverseKinematics(s.scene.truth, base_from_platform);
    for (int i = 0; i < kNumLegs; ++i) readings[i] += Uniform(-s.scene.noise.leg, s.scene.noise.leg);
    s.input.legs.push_back(readings);
    s.input.fk_start.push_back(nominal.PoseFromVector(v));
  }
  if (focal_error != 0) {
    StatusOr<std::vector<Pose>> biased = s.models.focal_length(seen, focal_error);
    EXPECT_TRUE(biased.ok()) << biased.status().message();
    if (biased.ok()) seen = *biased;
  }
  for (Pose& pose : seen) {
    for (int k = 0; k < 3; ++k) pose.position[k] += Uniform(-s.scene.noise.position, s.scene.noise.position);
    const Eigen::Vector3d turn =
        DegToRad(s.scene.noise.angle_deg) * Eigen::Vector3d(Uniform(-1, 1), Uniform(-1, 1), Uniform(-1, 1));
    pose.rotation = Eigen::AngleAxisd(turn.norm(), turn.normalized()).toRotationMatrix() * pose.rotation;
  }
  s.input.camera_from_target = seen;
  return s;
}

std::optional<CameraFrameResiduals> Diagnose(const SceneInput& s, const JobHooks& hooks = {}) {
  RegistrationOptions registration;  // as calibrate --session weighs the closure
  registration.position_sigma = s.scene.noise.PositionStdDev();
  registration.angle_sigma_deg = RadToDeg(s.scene.noise.AngleStdDevRad());
  const CalibrationOptions calibration = SessionCalibrationOptions(s.scene.noise, OutlierScreening{true});
  StatusOr<CameraCalibrationResult> result =
      CalibrateFromCameraPoses(s.scene.nominal, s.input, registration, calibration);
  EXPECT_TRUE(result.ok()) << result.status().message();
  if (!result.ok()) return std::nullopt;
  return SessionCameraFrameResiduals(s.scene.nominal, s.input, *result, registration, calibration, s.models, hooks);
}

TEST(SessionCameraFrameResiduals, CleanSessionNoFindingNoSimulation) {
  const std::optional<CameraFrameResiduals> r = Diagnose(MakeInput(0));
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->images, 40);
  EXPECT_FALSE(r->signatures.has_value());
  EXPECT_EQ(CameraFrameFindingText(*r), "no bias along the optical axis");
}

TEST(SessionCameraFrameResiduals, FocalLengthErrorIsSimulatedAndNamed) {
  const std::optional<CameraFrameResiduals> r = Diagnose(MakeInput(0.005));
  ASSERT_TRUE(r.has_value());
  ASSERT_TRUE(r->signatures.has_value());
  const CameraFrameFinding finding = DiagnoseCameraFrameBias(*r);
  EXPECT_EQ(finding.cause, BiasCause::kFocalLength);
  EXPECT_NEAR(finding.implied_error, 0.005, 0.001);
  EXPECT_THAT(CameraFrameFindingText(*r), HasSubstr("points to the focal length (camera depths about 0.4"));
  // A plain depth scale is not what this lens does: its lateral slopes differ.
  EXPECT_GT(std::abs(r->signatures->focal_length.x_slope), 0.05);
}

TEST(SessionCameraFrameResiduals, TooFewImagesWarnInsteadOfFailing) {
  SceneInput s = MakeInput(0);
  CameraCalibrationResult result;
  result.calibration.robot = s.scene.truth;
  result.registration.base_from_camera = s.scene.base_from_camera;
  result.registration.platform_from_target = s.scene.platform_from_target;
  s.input.camera_from_target.resize(2);
  s.input.legs.resize(2);
  std::vector<std::string> notes;
  JobHooks hooks;
  hooks.note = [&](const std::string& line) { notes.push_back(line); };
  EXPECT_FALSE(SessionCameraFrameResiduals(s.scene.nominal, s.input, result, {}, {}, s.models, hooks).has_value());
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_THAT(notes[0], HasSubstr("warning: no bias diagnosis: camera-frame residuals: 2 images"));
}

TEST(FormatCameraFrameLine, FiguresToTheirStandardErrorAndTheFinding) {
  CameraFrameResiduals r;
  r.images = 24;
  r.axes[0] = {0.00003, 0.003, 0.00061, 0.05, 0, 0.001, 0, 0.001};
  r.axes[1] = {-0.0002, 0.003, 0.00061, -0.33, 0, 0.001, 0, 0.001};
  r.axes[2] = {0.0123, 0.0044, 0.0009, 13.7, -0.0049, 0.0004, -0.0049, 0.0004};
  EXPECT_EQ(FormatCameraFrameLine(r, "cm"),
            "camera-frame residuals (cm, 24 images, mean ± standard error; robot − camera): x +0.00003 ± 0.00061, "
            "y -0.00020 ± 0.00061, z +0.01230 ± 0.00090 (t = +13.7, depth slope -0.490 % ± 0.040 %): a bias along "
            "the optical axis; points to the focal length (camera depths about 0.49 % too long)");
  r.images = 9;
  EXPECT_THAT(FormatCameraFrameLine(r, "mm"), StartsWith("camera-frame residuals (mm, 9 images"));
  EXPECT_THAT(FormatCameraFrameLine(r, "mm"), HasSubstr("too few images to diagnose a bias (10 needed)"));
}

TEST(FormatCameraFrameLine, FixedLikeShowsTwoDigitsOfTheUncertainty) {
  EXPECT_EQ(FixedLike(0.0123456, 0.00091), "+0.01235");
  EXPECT_EQ(FixedLike(-1.5, 0.25), "-1.50");
  EXPECT_EQ(FixedLike(123.4, 12, false), "123");
  EXPECT_EQ(FixedLike(0.5, 0), "+0.5000");
}

}  // namespace
}  // namespace hexcal::workflow
