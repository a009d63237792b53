// Each calibration image's closure (docs/calibration.md, "Closure by
// image"): the calibrated robot's FK from the image's leg readings against
// the pose its board shows (X · B · Y⁻¹). An image whose readings the
// outlier screening excluded is left out of the closure's RMS, as it is of
// the registration, and named with its cause: a board pose that disagrees
// with most of its legs is a swapped or mislabelled image, not a camera
// fault; one or two legs off are wrong readings.
//
//   report.closure_by_image = ClosureByImage(result, rows);
//   std::cout << ImageClosureLines(report);
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/registration.h"
#include "core/session.h"
#include "core/status.h"
#include "session/json_fields.h"

namespace hexcal::workflow {

struct ImageClosure {
  std::string image;             // legs.csv's image name
  std::optional<int> legs_line;  // its line in legs.csv, when known
  bool converged = false;        // FK converged (else the errors are 0)
  double position = 0;           // |P_fk − P_board|, robot unit
  double angle_deg = 0;          // rotation between them, degrees
  bool left_out = false;         // not in the closure RMS (it holds an excluded reading)
  std::vector<int> excluded_legs;  // legs (1..6) whose reading of this image was excluded
};

// A calibration image's name and legs.csv line, in the order of the result's measurements.
struct ImageName {
  std::string image;
  std::optional<int> legs_line;
};

std::vector<ImageClosure> ClosureByImage(const CameraCalibrationResult& result, const std::vector<ImageName>& names);

// At least this many of an image's six readings excluded: the image itself
// is wrong (its board pose is another pose's), not a reading.
constexpr int kWrongImageLegs = 4;

// Why an image was left out, for the summary and the verdict:
// "its board pose disagrees with 6 of 6 legs: a swapped or mislabelled image?"
// In a points session (`instrument` kPoints) the words are the tracker's:
// "its tracker pose disagrees with 6 of 6 legs: a swapped or mislabelled pose?".
std::string LeftOutCause(const ImageClosure& closure, Instrument instrument = Instrument::kCamera);
// The same in a few words: "a swapped or mislabelled image?", "a wrong reading on leg 3".
std::string ShortCause(const ImageClosure& closure, Instrument instrument = Instrument::kCamera);
// "view_0005.png (legs.csv line 7)".
std::string ImageLabel(const ImageClosure& closure);

// The summary's lines: each left-out image with its cause, then the worst
// image that counts, against the RMS.
std::string ImageClosureLines(const std::vector<ImageClosure>& closures, double closure_rms, const std::string& unit,
                              Instrument instrument = Instrument::kCamera);

nlohmann::json ImageClosuresJson(const std::vector<ImageClosure>& closures);
// Reads the array ImageClosuresJson wrote as `key` of `fields` (errors go
// to `fields`); none when the key is absent (older reports).
std::vector<ImageClosure> ImageClosuresFromJson(JsonFields& fields, const std::string& key);

}  // namespace hexcal::workflow
