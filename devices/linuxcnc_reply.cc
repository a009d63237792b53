#include "devices/linuxcnc_reply.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace hexcal::workflow {

std::string UpperCase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::toupper(c); });
  return text;
}

std::vector<std::string> ReplyWords(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

std::string JoinWords(const std::vector<std::string>& words) {
  std::string text;
  for (const std::string& word : words) text += (text.empty() ? "" : " ") + word;
  return text;
}

bool ParseFiniteNumber(const std::string& text, double* value) {
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return end != text.c_str() && *end == '\0' && std::isfinite(*value);
}

std::optional<Vector6d> SixNumbersAfter(const std::string& key, const std::string& reply) {
  const std::vector<std::string> words = ReplyWords(reply);
  if (words.size() != 7 || UpperCase(words[0]) != UpperCase(key)) return std::nullopt;
  Vector6d values;
  for (int k = 0; k < 6; ++k)
    if (!ParseFiniteNumber(words[k + 1], &values[k])) return std::nullopt;
  return values;
}

}  // namespace hexcal::workflow
