#include "session/image_closure.h"

#include <algorithm>
#include <sstream>


namespace hexcal::workflow {

std::vector<ImageClosure> ClosureByImage(const CameraCalibrationResult& result, const std::vector<ImageName>& names) {
  std::vector<ImageClosure> closures;
  const std::vector<int>& left_out = result.closure_left_out;
  for (size_t j = 0; j < result.closure_rows.size() && j < names.size(); ++j) {
    const ValidationRow& row = result.closure_rows[j];
    ImageClosure closure{names[j].image, names[j].legs_line, row.ok, row.ok ? row.position_error : 0,
                         row.ok ? row.orientation_error_deg : 0,
                         std::binary_search(left_out.begin(), left_out.end(), static_cast<int>(j)), {}};
    closures.push_back(std::move(closure));
  }
  for (size_t leg = 0; leg < result.calibration.legs.size(); ++leg)
    for (const RowOutlier& o : result.calibration.legs[leg].outliers)
      if (o.excluded && o.measurement >= 0 && static_cast<size_t>(o.measurement) < closures.size())
        closures[o.measurement].excluded_legs.push_back(static_cast<int>(leg) + 1);
  return closures;
}

std::string ImageLabel(const ImageClosure& closure) {
  return closure.image + (closure.legs_line ? " (legs.csv line " + std::to_string(*closure.legs_line) + ")" : "");
}

std::string ShortCause(const ImageClosure& closure, Instrument instrument) {
  const int legs = static_cast<int>(closure.excluded_legs.size());
  if (legs >= kWrongImageLegs) return "a swapped or mislabelled " + std::string(MeasurementNoun(instrument)) + "?";
  if (legs == 0) return "left out of the registration";
  std::string list;
  for (int leg : closure.excluded_legs) list += (list.empty() ? "" : ", ") + std::to_string(leg);
  return std::string(legs == 1 ? "a wrong reading on leg " : "wrong readings on legs ") + list;
}

std::string LeftOutCause(const ImageClosure& closure, Instrument instrument) {
  const int legs = static_cast<int>(closure.excluded_legs.size());
  const bool points = instrument == Instrument::kPoints;
  if (legs >= kWrongImageLegs)
    return std::string(points ? "its tracker pose" : "its board pose") + " disagrees with " + std::to_string(legs) +
           " of 6 legs: " + ShortCause(closure, instrument) +
           (points ? " (check that its points were measured at legs.csv's pose)"
                   : " (check that it was taken at legs.csv's pose)");
  if (legs == 0) return ShortCause(closure, instrument);
  return ShortCause(closure, instrument) + " (check the sensor and legs.csv)";
}

std::string ImageClosureLines(const std::vector<ImageClosure>& closures, double closure_rms, const std::string& unit,
                              Instrument instrument) {
  std::ostringstream out;
  out.precision(4);
  const ImageClosure* worst = nullptr;
  for (const ImageClosure& c : closures) {
    if (c.left_out) {
      out << "left out: " << ImageLabel(c) << ", closure ";
      if (c.converged) {
        out << c.position << " " << unit << ", " << c.angle_deg << " deg";
      } else {
        out << "unknown (FK did not converge)";
      }
      out << ": " << LeftOutCause(c, instrument) << "\n";
    } else if (c.converged && (worst == nullptr || c.position > worst->position)) {
      worst = &c;
    }
  }
  if (worst != nullptr && closure_rms > 0)
    out << "closure by " << MeasurementNoun(instrument) << ": worst " << ImageLabel(*worst) << " " << worst->position << " " << unit << ", "
        << worst->angle_deg << " deg (" << worst->position / closure_rms << "× the RMS)\n";
  return out.str();
}

nlohmann::json ImageClosuresJson(const std::vector<ImageClosure>& closures) {
  nlohmann::json rows = nlohmann::json::array();
  for (const ImageClosure& c : closures) {
    rows.push_back({{"image", c.image},
                    {"legs_line", c.legs_line ? nlohmann::json(*c.legs_line) : nlohmann::json(nullptr)},
                    {"converged", c.converged},
                    {"position", c.position},
                    {"angle_deg", c.angle_deg},
                    {"left_out", c.left_out},
                    {"excluded_legs", c.excluded_legs}});
  }
  return rows;
}

std::vector<ImageClosure> ImageClosuresFromJson(JsonFields& fields, const std::string& key) {
  std::vector<ImageClosure> closures;
  if (!fields.Has(key)) return closures;
  for (JsonFields c : fields.Array(key)) {
    const std::optional<int> line = c.Has("legs_line") ? std::optional<int>(c.Int("legs_line")) : std::nullopt;
    closures.push_back({c.String("image"), line, c.Bool("converged"), c.Number("position"), c.Number("angle_deg"),
                        c.Bool("left_out"), c.Ints("excluded_legs")});
  }
  return closures;
}

}  // namespace hexcal::workflow
