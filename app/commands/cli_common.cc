#include "app/commands/cli_common.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "core/csv.h"

namespace hexcal::cli {

int ExitCodeFor(const Status& status) {
  switch (status.kind()) {
    case StatusKind::kOk:
      return kExitOk;
    case StatusKind::kBadInput:
      return kExitBadInput;
    case StatusKind::kFailed:
    case StatusKind::kCancelled:
      return kExitFailure;
    case StatusKind::kIo:
      return kExitIo;
    case StatusKind::kBusy:
      return kExitBusy;
  }
  return kExitFailure;
}

int ReportError(std::ostream& err, const std::string& command, const Status& status) {
  err << "hexcal " << command << ": " << status.message() << "\n";
  return ExitCodeFor(status);
}

Status InFlagWords(const Status& status, const OptionFlagNames& flags) {
  const auto flag = flags.find(status.option());
  return flag == flags.end() ? status : status.WithOptionName(flag->second);
}

int ReportError(std::ostream& err, const std::string& command, const Status& status, const OptionFlagNames& flags) {
  return ReportError(err, command, InFlagWords(status, flags));
}

std::string JsonText(const nlohmann::json& json) {
  return json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

CLI::Validator CountRange(long long min, long long max, const std::string& why) {
  const std::string range = "[" + std::to_string(min) + ", " + std::to_string(max) + "]";
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        long long value = 0;
        size_t used = 0;
        try {
          value = std::stoll(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == 0 || used != text.size()) return "'" + text + "' is not a whole number";
        if (value >= min && value <= max) return "";
        return text + " is outside " + range + (why.empty() ? "" : " (" + why + ")");
      },
      "INT in " + range);
}

namespace {

bool AllDigits(const std::string& text, size_t begin) {
  return begin < text.size() &&
         std::all_of(text.begin() + begin, text.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
}

// What is wrong with `text` as a whole number of type INT or UINT, or "".
std::string WholeNumberProblem(const std::string& text, bool is_unsigned) {
  const size_t digits = !text.empty() && (text[0] == '-' || text[0] == '+') ? 1 : 0;
  if (!AllDigits(text, digits)) return Excerpt(text) + " is not a whole number in decimal digits";
  if (text.size() > digits + 1 && text[digits] == '0')
    return Excerpt(text) + ": a leading 0 (read as octal elsewhere); write the number without it";
  if (is_unsigned && text[0] == '-') return text + " is negative";
  const char* first = text.data() + (text[0] == '+' ? 1 : 0);
  const char* last = text.data() + text.size();
  std::errc error{};
  if (is_unsigned) {
    uint64_t value = 0;
    error = std::from_chars(first, last, value).ec;
  } else {
    int64_t value = 0;
    error = std::from_chars(first, last, value).ec;
  }
  if (error == std::errc()) return "";
  return text + " is outside [" +
         (is_unsigned ? "0, 18446744073709551615" : "-9223372036854775808, 9223372036854775807") + "]";
}

}  // namespace

CLI::Validator DecimalNumber(const std::string& type) {
  return CLI::Validator(
      [type](std::string& text) -> std::string {
        if (type != "FLOAT") return WholeNumberProblem(text, type == "UINT");
        // ParseNumber (from_chars) reads decimal only: "0x10" stops at the x.
        return ParseNumber(text).ok() ? "" : Excerpt(text) + " is not a finite decimal number";
      },
      "");
}

StatusOr<std::vector<double>> ParseNumberList(const std::string& text, int count, const std::string& what) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    StatusOr<double> value = ParseNumber(item);
    if (!value.ok()) return Status::BadInput(what + ": '" + item + "' is not a finite number");
    values.push_back(*value);
  }
  if (static_cast<int>(values.size()) != count) {
    return Status::BadInput(what + ": expected " + std::to_string(count) + " comma-separated numbers, got " +
                            std::to_string(values.size()));
  }
  return values;
}

ProgressBar::ProgressBar(std::string label) : label_(std::move(label)), enabled_(isatty(STDERR_FILENO) != 0) {}

ProgressBar::~ProgressBar() {
  if (enabled_ && last_percent_ >= 0) std::cerr << "\n";
}

void ProgressBar::Update(int done, int total) {
  if (!enabled_ || total <= 0) return;
  const int percent = static_cast<int>(100.0 * done / total);
  if (percent == last_percent_) return;
  last_percent_ = percent;
  const int width = 30, filled = width * percent / 100;
  std::cerr << "\r" << label_ << " [" << std::string(filled, '#') << std::string(width - filled, ' ') << "] " << percent
            << "% (" << done << "/" << total << ")" << std::flush;
}

TerminalJob::TerminalJob(std::string label, std::ostream* log) {
  if (!label.empty()) bar_ = std::make_unique<ProgressBar>(label);
  hooks_.progress = [this](int done, int total) {
    if (bar_) bar_->Update(done, total);
  };
  hooks_.stage = [this](const std::string& stage) {
    bar_.reset();  // ends the previous bar's line first
    bar_ = std::make_unique<ProgressBar>(stage);
  };
  hooks_.note = [this, log](const std::string& line) {
    if (log == nullptr) return;
    bar_.reset();
    *log << line << "\n" << std::flush;
  };
}

}  // namespace hexcal::cli
