#include "tests/test_support.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace hexcal::testing {

std::mt19937_64& TestRng() {
  static std::mt19937_64 rng(1);
  return rng;
}

void ReseedTestRng(uint64_t seed) { TestRng().seed(seed); }

double Uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(TestRng()); }

std::filesystem::path SourceDir() {
  if (const char* dir = std::getenv("HEXCAL_SOURCE_DIR")) return dir;
  return std::filesystem::path(__FILE__).parent_path().parent_path();
}

TempDir::TempDir() {
  static int counter = 0;
  std::random_device rd;
  path_ = std::filesystem::temp_directory_path() /
          ("hexcal_test_" + std::to_string(rd()) + "_" + std::to_string(counter++));
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

void WriteTextFile(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::string ReadTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace hexcal::testing
