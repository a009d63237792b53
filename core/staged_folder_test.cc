#include "core/staged_folder.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/atomic_file.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::ReadTextFile;
using ::hexcal::testing::TempDir;
using ::hexcal::testing::WriteTextFile;

namespace fs = std::filesystem;

int EntriesIn(const fs::path& folder) {
  int count = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(folder)) ++count;
  return count;
}

TEST(StagedFolder, PublishesANewFolderWhole) {
  TempDir dir;
  const std::string results = dir.File("results");
  StatusOr<StagedFolder> staged = StagedFolder::Begin(results);
  ASSERT_TRUE(staged.ok()) << staged.status().message();
  ASSERT_TRUE(WriteFileAtomically(staged->File("a.txt"), "new a").ok());
  EXPECT_FALSE(fs::exists(results));  // nothing is visible before Publish
  ASSERT_TRUE(staged->Publish().ok());
  EXPECT_EQ(ReadTextFile(results + "/a.txt"), "new a");
  EXPECT_EQ(EntriesIn(dir.path()), 1);  // no staging folder left
}

TEST(StagedFolder, ReplacesAnOldFolderAndRemovesWhatOnlyItHad) {
  TempDir dir;
  const std::string results = dir.File("results");
  fs::create_directory(results);
  WriteTextFile(results + "/a.txt", "old a");
  WriteTextFile(results + "/old-only.txt", "old");
  StatusOr<StagedFolder> staged = StagedFolder::Begin(results);
  ASSERT_TRUE(staged.ok());
  ASSERT_TRUE(WriteFileAtomically(staged->File("a.txt"), "new a").ok());
  EXPECT_EQ(ReadTextFile(results + "/a.txt"), "old a");
  ASSERT_TRUE(staged->Publish().ok());
  EXPECT_EQ(ReadTextFile(results + "/a.txt"), "new a");
  EXPECT_FALSE(fs::exists(results + "/old-only.txt"));
  EXPECT_EQ(EntriesIn(dir.path()), 1);
}

TEST(StagedFolder, AnUnpublishedFolderIsRemovedAndStaleOnesAreCleanedAtTheNextBegin) {
  TempDir dir;
  const std::string results = dir.File("results");
  {
    StatusOr<StagedFolder> abandoned = StagedFolder::Begin(results);
    ASSERT_TRUE(abandoned.ok());
    WriteTextFile(abandoned->File("half.txt"), "half");
  }
  EXPECT_EQ(EntriesIn(dir.path()), 0);
  fs::create_directory(dir.File(".results.new-KILLED"));  // left by a kill -9
  WriteTextFile(dir.File(".results.new-KILLED/x"), "x");
  StatusOr<StagedFolder> staged = StagedFolder::Begin(results);
  ASSERT_TRUE(staged.ok());
  EXPECT_FALSE(fs::exists(dir.File(".results.new-KILLED")));
}

TEST(StagedFolder, AFinalFolderThatIsASymlinkIsReplacedAndItsTargetLeftAlone) {
  TempDir dir, outside;
  WriteTextFile(outside.File("precious.txt"), "keep me");
  const std::string results = dir.File("results");
  fs::create_directory_symlink(outside.path(), results);
  StatusOr<StagedFolder> staged = StagedFolder::Begin(results);
  ASSERT_TRUE(staged.ok());
  ASSERT_TRUE(WriteFileAtomically(staged->File("report.json"), "{}").ok());
  ASSERT_TRUE(staged->Publish().ok());
  EXPECT_FALSE(fs::is_symlink(results));
  EXPECT_TRUE(fs::exists(results + "/report.json"));
  EXPECT_EQ(ReadTextFile(outside.File("precious.txt")), "keep me");
  EXPECT_FALSE(fs::exists(outside.File("report.json")));
}

}  // namespace
}  // namespace hexcal
