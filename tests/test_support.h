// Helpers shared by the tests: a reseeded RNG, Eigen comparisons, temporary
// directories that clean up after themselves and the message of a result that
// must be an error.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <filesystem>
#include <random>
#include <string>

namespace hexcal::testing {

// The per-test RNG; reseeded before every test by the shared main.
std::mt19937_64& TestRng();
void ReseedTestRng(uint64_t seed);
double Uniform(double lo, double hi);

// Root of the source tree (resources/, tests/data/).
std::filesystem::path SourceDir();

// A fresh directory under the system temp dir, removed on destruction.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::string File(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

void WriteTextFile(const std::string& path, const std::string& text);
std::string ReadTextFile(const std::string& path);

// The message of `result` (a StatusOr, or any type with ok() and status()),
// which must be an error: a success fails the test, naming `input`, and gives
// "", so that the caller's comparison of the message fails too.
//   std::string ParseError(const std::string& yaml) { return ErrorMessage(ParseTargetYaml(yaml, "t.yaml"), yaml); }
template <typename Result>
std::string ErrorMessage(const Result& result, const std::string& input = "") {
  EXPECT_FALSE(result.ok()) << "no error for: " << input;
  return result.ok() ? "" : result.status().message();
}

template <typename A, typename B>
::testing::AssertionResult MatrixNear(const Eigen::MatrixBase<A>& a, const Eigen::MatrixBase<B>& b, double tolerance) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) {
    return ::testing::AssertionFailure() << "size mismatch";
  }
  const double diff = (a - b).cwiseAbs().maxCoeff();
  if (diff <= tolerance) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "max |a-b| = " << diff << " > " << tolerance << "\na =\n"
                                       << a << "\nb =\n"
                                       << b;
}

}  // namespace hexcal::testing
