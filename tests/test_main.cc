// The gtest main shared by every test executable: each test starts from a
// known RNG seed (printed on failure), so a failing random test can be rerun.
#include <gtest/gtest.h>

#include <cstdlib>

#include "tests/test_support.h"

namespace {

class ReseedListener : public testing::EmptyTestEventListener {
  void OnTestStart(const testing::TestInfo& info) override {
    hexcal::testing::ReseedTestRng(std::hash<std::string>{}(std::string(info.test_suite_name()) + "." + info.name()));
  }
};

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  testing::UnitTest::GetInstance()->listeners().Append(new ReseedListener);
  return RUN_ALL_TESTS();
}
