#include "session/calibration_report.h"

#include "core/atomic_file.h"
#include "session/camera_frame_diagnosis.h"
#include "session/json_fields.h"
#include "session/json_forms.h"
#include "session/results_files.h"

namespace hexcal::workflow {
namespace {

nlohmann::json Optional(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

std::vector<double> Values(const Vector6d& v) { return {v.data(), v.data() + 6}; }

Vector6d VectorOf(const std::vector<double>& values) {
  Vector6d v;
  for (int k = 0; k < 6; ++k) v[k] = values[k];
  return v;
}

nlohmann::json StatsJson(const PoseErrorStats& stats) {
  return {{"position_rms", stats.position_rms},
          {"position_max", stats.position_max},
          {"orientation_rms", stats.orientation_rms},
          {"orientation_max", stats.orientation_max},
          {"failed", stats.failed}};
}

PoseErrorStats StatsFromJson(JsonFields fields) {
  return {fields.Number("position_rms"), fields.Number("position_max"), fields.Number("orientation_rms"),
          fields.Number("orientation_max"), fields.Int("failed")};
}

nlohmann::json ValidationJson(const ValidationSummary& validation) {
  nlohmann::json per_image = nlohmann::json::array();
  for (const HeldOutImage& row : validation.per_image) {
    per_image.push_back({{"image", row.image},
                         {"position_before", Optional(row.position_before)},
                         {"position_after", Optional(row.position_after)},
                         {"orientation_before", Optional(row.orientation_before)},
                         {"orientation_after", Optional(row.orientation_after)}});
  }
  return {{"rows", validation.rows},
          {"before", StatsJson(validation.before)},
          {"after", StatsJson(validation.after)},
          {"per_image", per_image}};
}

ValidationSummary ValidationFromJson(JsonFields fields) {
  ValidationSummary validation;
  validation.rows = fields.Int("rows");
  validation.before = StatsFromJson(fields.Object("before"));
  validation.after = StatsFromJson(fields.Object("after"));
  for (JsonFields row : fields.Array("per_image")) {
    validation.per_image.push_back({row.String("image"), row.OptionalNumber("position_before"),
                                    row.OptionalNumber("position_after"), row.OptionalNumber("orientation_before"),
                                    row.OptionalNumber("orientation_after")});
  }
  return validation;
}

nlohmann::json RegistrationJson(const RegistrationSummary& r) {
  return {{"position_rms", r.position_rms},
          {"angle_rms_deg", r.angle_rms_deg},
          {"position_max", r.position_max},
          {"angle_max_deg", r.angle_max_deg},
          {"base_from_camera", Values(r.base_from_camera)},
          {"platform_from_target", Values(r.platform_from_target)}};
}

RegistrationSummary RegistrationFromJson(JsonFields fields) {
  RegistrationSummary r;
  r.position_rms = fields.Number("position_rms");
  r.angle_rms_deg = fields.Number("angle_rms_deg");
  r.position_max = fields.Number("position_max");
  r.angle_max_deg = fields.Number("angle_max_deg");
  r.base_from_camera = VectorOf(fields.Numbers("base_from_camera", 6));
  r.platform_from_target = VectorOf(fields.Numbers("platform_from_target", 6));
  return r;
}

nlohmann::json ParametersJson(const std::vector<ParameterEstimate>& parameters) {
  nlohmann::json rows = nlohmann::json::array();
  for (const ParameterEstimate& p : parameters) {
    rows.push_back({{"leg", p.leg},
                    {"name", p.name},
                    {"nominal", p.nominal},
                    {"estimate", p.estimate},
                    {"sigma", Optional(p.sigma)}});
  }
  return rows;
}

nlohmann::json LegsJson(const std::vector<LegFit>& legs) {
  nlohmann::json rows = nlohmann::json::array();
  for (const LegFit& leg : legs) {
    rows.push_back({{"leg", leg.leg},
                    {"variance_factor", leg.variance_factor},
                    {"residual_rms", leg.residual_rms},
                    {"iterations", leg.iterations},
                    {"termination", leg.termination},
                    {"condition_number", leg.condition_number ? nlohmann::json(*leg.condition_number)
                                                              : nlohmann::json(nullptr)}});
  }
  return rows;
}

nlohmann::json OutliersJson(const std::vector<OutlierReading>& outliers) {
  nlohmann::json rows = nlohmann::json::array();
  for (const OutlierReading& o : outliers) {
    rows.push_back({{"image", o.image},
                    {"legs_line", o.legs_line ? nlohmann::json(*o.legs_line) : nlohmann::json(nullptr)},
                    {"leg", o.leg},
                    {"residual", o.residual},
                    {"z", o.z},
                    {"excluded", o.excluded}});
  }
  return rows;
}

nlohmann::json NoiseJson(const std::optional<NoiseExpectation>& noise) {
  if (!noise) return nullptr;
  return {{"position", noise->model.position},
          {"angle_deg", noise->model.angle_deg},
          {"leg", noise->model.leg},
          {"expected_position_rms", noise->position_rms},
          {"expected_orientation_rms_deg", noise->orientation_rms_deg}};
}

// Reports written before the verdict have no "noise_model": read as none.
std::optional<NoiseExpectation> NoiseFromJson(JsonFields& fields) {
  if (!fields.Has("noise_model")) return std::nullopt;
  JsonFields n = fields.Object("noise_model");
  NoiseExpectation noise;
  noise.model = {n.Number("position"), n.Number("angle_deg"), n.Number("leg")};
  noise.position_rms = n.Number("expected_position_rms");
  noise.orientation_rms_deg = n.Number("expected_orientation_rms_deg");
  return noise;
}

nlohmann::json AxisJson(const AxisResiduals& axis) {
  return {{"mean", axis.mean},
          {"std", axis.std_dev},
          {"standard_error", axis.standard_error},
          {"t", axis.t},
          {"depth_slope", axis.depth_slope},
          {"depth_slope_se", axis.depth_slope_se},
          {"scale_slope", axis.scale_slope},
          {"scale_slope_se", axis.scale_slope_se}};
}

AxisResiduals AxisFromJson(JsonFields fields) {
  return {fields.Number("mean"),        fields.Number("std"),           fields.Number("standard_error"),
          fields.Number("t"),           fields.Number("depth_slope"),   fields.Number("depth_slope_se"),
          fields.Number("scale_slope"), fields.Number("scale_slope_se")};
}

nlohmann::json SignatureJson(const BiasSignature& s) {
  return {{"depth_slope", s.depth_slope}, {"x_slope", s.x_slope}, {"y_slope", s.y_slope}};
}

BiasSignature SignatureFromJson(JsonFields fields) {
  return {fields.Number("depth_slope"), fields.Number("x_slope"), fields.Number("y_slope")};
}

// "finding" follows from the figures (CameraFrameFindingText): written for
// the reader of the file, not read back.
nlohmann::json CameraFrameJson(const std::optional<CameraFrameResiduals>& r) {
  if (!r) return nullptr;
  nlohmann::json axes;
  for (int a = 0; a < 3; ++a) axes[std::string(1, "xyz"[a])] = AxisJson(r->axes[a]);
  const nlohmann::json signatures = r->signatures
                                        ? nlohmann::json{{"focal_length", SignatureJson(r->signatures->focal_length)},
                                                         {"target_scale", SignatureJson(r->signatures->target_scale)}}
                                        : nlohmann::json(nullptr);
  return {{"images", r->images},
          {"fk_failed", r->fk_failed},
          {"depth_min", r->depth_min},
          {"depth_max", r->depth_max},
          {"axes", axes},
          {"signatures", signatures},
          {"finding", CameraFrameFindingText(*r)}};
}

// Reports written before the diagnosis have no "camera_frame_residuals".
std::optional<CameraFrameResiduals> CameraFrameFromJson(JsonFields& fields) {
  if (!fields.Has("camera_frame_residuals")) return std::nullopt;
  JsonFields c = fields.Object("camera_frame_residuals");
  CameraFrameResiduals r;
  r.images = c.Int("images");
  r.fk_failed = c.Int("fk_failed");
  r.depth_min = c.Number("depth_min");
  r.depth_max = c.Number("depth_max");
  JsonFields axes = c.Object("axes");
  for (int a = 0; a < 3; ++a) r.axes[a] = AxisFromJson(axes.Object(std::string(1, "xyz"[a])));
  if (c.Has("signatures")) {
    JsonFields s = c.Object("signatures");
    r.signatures =
        BiasSignatures{SignatureFromJson(s.Object("focal_length")), SignatureFromJson(s.Object("target_scale"))};
  }
  return r;
}

// Reports written before the screening have neither key: read as none.
void OutliersFromJson(JsonFields& fields, CalibrationReport* report) {
  if (fields.Has("outlier_screening")) {
    JsonFields s = fields.Object("outlier_screening");
    report->screening = OutlierScreeningSummary{s.Number("threshold"), s.Bool("keep"), s.Bool("screened")};
  }
  if (!fields.Has("outliers")) return;
  for (JsonFields o : fields.Array("outliers")) {
    const std::optional<int> line = o.Has("legs_line") ? std::optional<int>(o.Int("legs_line")) : std::nullopt;
    report->outliers.push_back(
        {o.String("image"), line, o.Int("leg"), o.Number("residual"), o.Number("z"), o.Bool("excluded")});
  }
}

// report.json but for the instrument.
nlohmann::json ReportJson(const CalibrationReport& report) {
  return {{"session", report.session},
          {"images", report.images},
          {"unusable_images", report.unusable_images},
          {"calibration_images", report.calibration_images},
          {"held_out_images", report.held_out_images},
          {"length_unit", report.length_unit},
          {"registration", RegistrationJson(report.registration)},
          {"closure_after_calibration",
           {{"position_rms", report.closure_position_rms},
            {"angle_rms_deg", report.closure_angle_rms_deg},
            {"by_image", ImageClosuresJson(report.closure_by_image)}}},
          {"validation", report.validation ? ValidationJson(*report.validation) : nlohmann::json(nullptr)},
          {"calibrated_robot", report.calibrated_robot},
          {"robot", RobotJson(report.robot)},
          {"parameters", ParametersJson(report.parameters)},
          {"legs", LegsJson(report.legs)},
          {"outlier_screening", report.screening ? nlohmann::json{{"threshold", report.screening->threshold},
                                                                  {"keep", report.screening->keep},
                                                                  {"screened", report.screening->screened}}
                                                 : nlohmann::json(nullptr)},
          {"outliers", OutliersJson(report.outliers)},
          {"noise_model", NoiseJson(report.noise)},
          {"method", report.from_pixels ? "from-pixels" : report.from_points ? "from-points" : "two-stage"},
          {"from_pixels", report.from_pixels ? ToJson(*report.from_pixels) : nlohmann::json(nullptr)},
          {"camera_frame_residuals", CameraFrameJson(report.camera_frame_residuals)}};
}

}  // namespace

nlohmann::json ToJson(const CalibrationReport& report) {
  nlohmann::json json = ReportJson(report);
  if (report.instrument != Instrument::kCamera) {  // a camera report as it always was
    json["instrument"] = InstrumentName(report.instrument);
    json["from_points"] = report.from_points ? ToJson(*report.from_points) : nlohmann::json(nullptr);
  }
  return json;
}

StatusOr<CalibrationReport> CalibrationReportFromJson(const nlohmann::json& json, const std::string& source) {
  JsonFields fields(json, source);
  CalibrationReport report;
  report.session = fields.String("session");
  if (fields.Has("instrument")) {
    const std::string instrument = fields.String("instrument");
    if (instrument == InstrumentName(Instrument::kPoints)) report.instrument = Instrument::kPoints;
    else if (instrument != InstrumentName(Instrument::kCamera)) fields.Fail("instrument", "expected camera or points");
  }
  report.images = fields.Int("images");
  report.unusable_images = fields.Int("unusable_images");
  report.calibration_images = fields.Int("calibration_images");
  report.held_out_images = fields.Int("held_out_images");
  report.length_unit = fields.String("length_unit");
  report.registration = RegistrationFromJson(fields.Object("registration"));
  JsonFields closure = fields.Object("closure_after_calibration");
  report.closure_position_rms = closure.Number("position_rms");
  report.closure_angle_rms_deg = closure.Number("angle_rms_deg");
  report.closure_by_image = ImageClosuresFromJson(closure, "by_image");
  if (fields.Has("validation")) report.validation = ValidationFromJson(fields.Object("validation"));
  report.calibrated_robot = fields.String("calibrated_robot");
  report.robot = RobotFromJson(fields.Object("robot"));
  for (JsonFields p : fields.Array("parameters")) {
    report.parameters.push_back(
        {p.Int("leg"), p.String("name"), p.Number("nominal"), p.Number("estimate"), p.OptionalNumber("sigma")});
  }
  if (fields.status().ok() && report.parameters.size() != static_cast<size_t>(kNumParams))
    fields.Fail("parameters", "expected " + std::to_string(kNumParams) + " parameters");
  for (JsonFields leg : fields.Array("legs")) {
    report.legs.push_back({leg.Int("leg"), leg.Number("variance_factor"), leg.Number("residual_rms"),
                           leg.Int("iterations"), leg.String("termination"), leg.OptionalNumber("condition_number")});
  }
  OutliersFromJson(fields, &report);
  report.noise = NoiseFromJson(fields);
  // Reports written before the calibration from pixels have no "from_pixels": two-stage.
  if (fields.Has("from_pixels")) report.from_pixels = PixelFitSummaryFromJson(fields.Object("from_pixels"));
  // Points reports written before the calibration from points have none: two-stage.
  if (fields.Has("from_points")) report.from_points = PointFitSummaryFromJson(fields.Object("from_points"));
  report.camera_frame_residuals = CameraFrameFromJson(fields);
  if (!fields.status().ok()) return fields.status();
  return report;
}

std::string CalibrationReportPath(const std::string& session_dir) {
  return ResultsFile(session_dir, kReportJson);
}

StatusOr<CalibrationReport> LoadCalibrationReport(const std::string& path) {
  StatusOr<std::string> text = ReadFileToString(path, kMaxJsonBytes);
  if (!text.ok()) return text.status();
  StatusOr<nlohmann::json> json = ParseJsonText(*text, path);
  if (!json.ok()) return json.status();
  return CalibrationReportFromJson(*json, path);
}

Status SaveCalibrationReport(const std::string& path, const CalibrationReport& report) {
  // A file name that is not UTF-8 is written with U+FFFD, never thrown on.
  const std::string text = ToJson(report).dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
  return WriteFileAtomically(path, text + "\n");
}

}  // namespace hexcal::workflow
