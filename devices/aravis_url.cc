// ParseAravisUrl (devices/aravis_frame_source.h): aravis:NAME[?exposure=US][&gain=DB].
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "devices/aravis_frame_source.h"

namespace hexcal::workflow {
namespace {

constexpr const char* kForm = "expected aravis:NAME[?exposure=US][&gain=DB], NAME as arv-tool-0.8 lists it";

Status BadAravisUrl(const std::string& url, const std::string& problem) {
  return Status::BadInput("camera '" + url + "': " + problem + "; " + kForm);
}

// The whole text as a finite number, or nullopt.
std::optional<double> ParseNumber(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (errno != 0 || end != text.c_str() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace

StatusOr<AravisUrl> ParseAravisUrl(const std::string& url) {
  const std::string prefix = "aravis:";
  if (url.compare(0, prefix.size(), prefix) != 0) return BadAravisUrl(url, "not an aravis: URL");
  const std::string rest = url.substr(prefix.size());
  const size_t question = rest.find('?');
  AravisUrl parsed;
  parsed.device_id = rest.substr(0, question);
  if (parsed.device_id.empty()) return BadAravisUrl(url, "no camera name after 'aravis:'");
  if (question == std::string::npos) return parsed;
  const std::string query = rest.substr(question + 1);
  size_t start = 0;
  while (start <= query.size()) {
    const size_t amp = query.find('&', start);
    const std::string pair = query.substr(start, amp == std::string::npos ? std::string::npos : amp - start);
    start = amp == std::string::npos ? query.size() + 1 : amp + 1;
    const size_t equals = pair.find('=');
    const std::string key = pair.substr(0, equals);
    const std::string text = equals == std::string::npos ? "" : pair.substr(equals + 1);
    std::optional<double>* slot = key == "exposure" ? &parsed.exposure_us : key == "gain" ? &parsed.gain_db : nullptr;
    if (slot == nullptr) return BadAravisUrl(url, "unknown option '" + key + "' (exposure, gain)");
    if (slot->has_value()) return BadAravisUrl(url, "'" + key + "' given twice");
    const std::optional<double> value = ParseNumber(text);
    if (!value) return BadAravisUrl(url, key + " '" + text + "' is not a number");
    if (key == "exposure" && *value <= 0)
      return BadAravisUrl(url, "exposure '" + text + "' must be a positive number of microseconds");
    *slot = value;
  }
  return parsed;
}

}  // namespace hexcal::workflow
