#include "core/atomic_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::ReadTextFile;
using ::hexcal::testing::TempDir;
using ::hexcal::testing::WriteTextFile;
using ::testing::HasSubstr;

std::vector<std::string> FileNamesIn(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

TEST(AtomicFileTest, RoundTripKeepsEveryByte) {
  TempDir dir;
  const std::string path = dir.File("plan.csv");
  std::string contents = "x,y\r\n1,2\n";
  contents.push_back('\0');
  contents += "\xff binary tail";
  ASSERT_TRUE(WriteFileAtomically(path, contents).ok());
  StatusOr<std::string> read = ReadFileToString(path);
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(*read, contents);
}

TEST(AtomicFileTest, EmptyContentsMakeAnEmptyFile) {
  TempDir dir;
  const std::string path = dir.File("empty.txt");
  ASSERT_TRUE(WriteFileAtomically(path, "").ok());
  StatusOr<std::string> read = ReadFileToString(path);
  ASSERT_TRUE(read.ok());
  EXPECT_EQ(*read, "");
}

TEST(AtomicFileTest, OverwriteKeepsOnlyTheNewContents) {
  TempDir dir;
  const std::string path = dir.File("robot.yaml");
  WriteTextFile(path, std::string(10000, 'o'));
  ASSERT_TRUE(WriteFileAtomically(path, "short").ok());
  EXPECT_EQ(ReadTextFile(path), "short");
}

TEST(AtomicFileTest, LeavesNoTemporaryFilesBehind) {
  TempDir dir;
  ASSERT_TRUE(WriteFileAtomically(dir.File("a.txt"), "one").ok());
  ASSERT_TRUE(WriteFileAtomically(dir.File("a.txt"), "two").ok());
  ASSERT_TRUE(WriteFileAtomically(dir.File("b.txt"), "three").ok());
  EXPECT_EQ(FileNamesIn(dir.path()), (std::vector<std::string>{"a.txt", "b.txt"}));
}

// Leftovers of killed writers: the next write of the same target removes the
// stale ones and nothing else (a fresh one may be a live writer's, another
// target's belong to that target, look-alike names are not temp files).
TEST(AtomicFileTest, WriteRemovesStaleTempFilesOfItsTarget) {
  TempDir dir;
  const auto make = [&](const std::string& name, std::chrono::minutes age) {
    WriteTextFile(dir.File(name), "partial");
    const auto when = std::filesystem::file_time_type::clock::now() - age;
    std::filesystem::last_write_time(dir.File(name), when);
  };
  const std::chrono::minutes stale = kStaleTempAge + std::chrono::minutes(1);
  make(".a.txt.tmp.Ab12Cd", stale);
  make(".a.txt.tmp.Zz99Yy", stale);
  make(".a.txt.tmp.fresh1", std::chrono::minutes(0));
  make(".b.txt.tmp.Ab12Cd", stale);
  make(".a.txt.tmp.toolong", stale);
  ASSERT_TRUE(WriteFileAtomically(dir.File("a.txt"), "new").ok());
  EXPECT_EQ(FileNamesIn(dir.path()),
            (std::vector<std::string>{".a.txt.tmp.fresh1", ".a.txt.tmp.toolong", ".b.txt.tmp.Ab12Cd", "a.txt"}));
  EXPECT_EQ(ReadTextFile(dir.File("a.txt")), "new");
}

TEST(AtomicFileTest, OverwriteKeepsThePermissionsOfTheTarget) {
  TempDir dir;
  const std::string path = dir.File("script.sh");
  WriteTextFile(path, "old");
  ASSERT_EQ(::chmod(path.c_str(), 0750), 0);
  ASSERT_TRUE(WriteFileAtomically(path, "new").ok());
  struct stat info;
  ASSERT_EQ(::stat(path.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 07777, 0750u);
}

TEST(AtomicFileTest, NewFileGetsTheModeThatTheUmaskAllows) {
  // mkstemp makes 0600 files; a new file must get 0666 minus the umask like
  // any other. Tests run on one thread, so changing the umask here is safe.
  TempDir dir;
  const std::string path = dir.File("plan.csv");
  const mode_t previous_umask = ::umask(027);
  const Status written = WriteFileAtomically(path, "x");
  ::umask(previous_umask);
  ASSERT_TRUE(written.ok()) << written.message();
  struct stat info;
  ASSERT_EQ(::stat(path.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 07777, 0640u) << std::oct << (info.st_mode & 07777);
}

TEST(AtomicFileTest, WritingIntoAMissingFolderFailsAndNamesThePath) {
  TempDir dir;
  const std::string path = dir.File("no_such_folder/robot.yaml");
  Status status = WriteFileAtomically(path, "x");
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr(path));
  EXPECT_THAT(status.message(), HasSubstr("No such file or directory"));
  EXPECT_EQ(FileNamesIn(dir.path()), std::vector<std::string>{});
}

TEST(AtomicFileTest, WritingOverAFolderFailsAndCleansUp) {
  TempDir dir;
  std::filesystem::create_directory(dir.path() / "taken");
  std::filesystem::create_directory(dir.path() / "taken" / "child");
  Status status = WriteFileAtomically(dir.File("taken"), "x");
  ASSERT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr(dir.File("taken")));
  EXPECT_EQ(FileNamesIn(dir.path()), std::vector<std::string>{"taken"});
}

TEST(AtomicFileTest, ReadingAMissingFileSaysSo) {
  TempDir dir;
  const std::string path = dir.File("missing.csv");
  StatusOr<std::string> read = ReadFileToString(path);
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.status().message(), path + ": no such file");
}

TEST(AtomicFileTest, ReadingAFolderSaysItIsAFolder) {
  TempDir dir;
  StatusOr<std::string> read = ReadFileToString(dir.path().string());
  ASSERT_FALSE(read.ok());
  EXPECT_THAT(read.status().message(), HasSubstr(dir.path().string()));
  EXPECT_THAT(read.status().message(), HasSubstr("is a directory"));
}

TEST(AtomicFileTest, ReadingAnUnreadableFileSaysSo) {
  if (::geteuid() == 0) GTEST_SKIP() << "root reads files whatever their mode";
  TempDir dir;
  const std::string path = dir.File("secret.csv");
  WriteTextFile(path, "x");
  ASSERT_EQ(::chmod(path.c_str(), 0), 0);
  StatusOr<std::string> read = ReadFileToString(path);
  ASSERT_FALSE(read.ok());
  EXPECT_THAT(read.status().message(), HasSubstr(path + ": cannot open"));
  EXPECT_EQ(read.status().kind(), StatusKind::kIo);  // the path is right; the system refused
}

// Bounded input (issue 13): a FIFO with no writer would block open(2) and
// read(2) for ever; a link to /dev/zero would be read until memory runs out.
TEST(AtomicFileTest, ReadingAFifoIsRefusedAtOnce) {
  TempDir dir;
  const std::string path = dir.File("robot.yaml");
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  StatusOr<std::string> read = ReadFileToString(path);
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.status().message(), path + ": not a regular file (a FIFO)");
}

TEST(AtomicFileTest, ReadingALinkToADeviceIsRefused) {
  TempDir dir;
  const std::string path = dir.File("legs.csv");
  std::filesystem::create_symlink("/dev/zero", path);
  StatusOr<std::string> read = ReadFileToString(path, kMaxTableBytes);
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.status().message(), path + ": not a regular file (a character device)");
}

// Issue 36: a dangling link said "no such file" though ls lists the name.
TEST(AtomicFileTest, ReadingADanglingLinkSaysItIsOne) {
  TempDir dir;
  const std::string path = dir.File("camera.yaml");
  std::filesystem::create_symlink(dir.File("gone.yaml"), path);
  StatusOr<std::string> read = ReadFileToString(path);
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.status().message(), path + ": a symbolic link to a missing file");
  EXPECT_EQ(CheckFileForReading(path, kMaxImageBytes).message(), path + ": a symbolic link to a missing file");
  EXPECT_EQ(CheckFileForReading(dir.File("none.png"), kMaxImageBytes).message(),
            dir.File("none.png") + ": no such file");
}

// Issue 36: one kind of error for a folder that cannot be made, whoever makes it.
TEST(AtomicFileTest, CreateFoldersNamesAFileInTheWayAsBadInput) {
  TempDir dir;
  EXPECT_TRUE(CreateFolders(dir.File("a/b/c")).ok());
  EXPECT_TRUE(CreateFolders(dir.File("a/b/c")).ok());
  WriteTextFile(dir.File("file"), "x");
  const Status under_a_file = CreateFolders(dir.File("file/sub"));
  EXPECT_EQ(under_a_file.kind(), StatusKind::kBadInput);
  EXPECT_EQ(under_a_file.message(), dir.File("file/sub") + ": cannot create the folder: Not a directory");
  EXPECT_EQ(CreateFolders(dir.File("file")).kind(), StatusKind::kBadInput);
}

// Issue 37: the tier of a failed file operation says what to fix. A path
// that names the wrong thing is bad input; a refusal of the system is I/O.
TEST(AtomicFileTest, FileSystemErrorSortsErrnoIntoBadInputAndIo) {
  for (int path_problem : {ENOENT, ENOTDIR, EISDIR, ENAMETOOLONG, ELOOP, EEXIST})
    EXPECT_EQ(FileSystemError("p", "cannot open", path_problem).kind(), StatusKind::kBadInput) << path_problem;
  for (int refusal : {EACCES, EPERM, EROFS, ENOSPC, EDQUOT, EIO})
    EXPECT_EQ(FileSystemError("p", "cannot open", refusal).kind(), StatusKind::kIo) << refusal;
  EXPECT_EQ(FileSystemError("p", "cannot open", EIO).message(), "p: cannot open: Input/output error");
}

TEST(AtomicFileTest, AReadThatFailsIsAnIoError) {
  // /proc/self/mem opens as a regular file of size 0, and reading address 0 fails with EIO.
  StatusOr<std::string> read = ReadFileToString("/proc/self/mem");
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.status().kind(), StatusKind::kIo);
  EXPECT_EQ(read.status().message(), "/proc/self/mem: read failed: Input/output error");
}

TEST(AtomicFileTest, AWriteTheSystemRefusesIsAnIoErrorAndAMissingFolderBadInput) {
  // sysfs refuses a new file, to root too (EACCES); a CI runner's user as well.
  const Status refused = WriteFileAtomically("/sys/hexcal-test.csv", "x");
  EXPECT_EQ(refused.kind(), StatusKind::kIo) << refused.message();
  EXPECT_EQ(CreateFolders("/sys/hexcal-test").kind(), StatusKind::kIo);
  TempDir dir;
  const Status no_folder = WriteFileAtomically(dir.File("missing/out.csv"), "x");
  EXPECT_EQ(no_folder.kind(), StatusKind::kBadInput) << no_folder.message();
  EXPECT_THAT(no_folder.message(), HasSubstr("No such file or directory"));
}

TEST(AtomicFileTest, ReadingAFileOverItsSizeCapIsRefused) {
  TempDir dir;
  const std::string path = dir.File("robot.yaml");
  WriteTextFile(path, std::string(2 * kMiB, 'x'));
  StatusOr<std::string> read = ReadFileToString(path, kMiB);
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.status().message(), path + ": 2.0 MiB is over the 1.0 MiB limit for this kind of file");
  EXPECT_TRUE(ReadFileToString(path, 2 * kMiB).ok());
}

// An output: a file is replaced only with --force; what is not a file never,
// since the rename would put a file in place of a device node or a FIFO.
TEST(AtomicFileTest, CheckOutputFreeRefusesWhatIsNotAFileEvenWithForce) {
  TempDir dir;
  const std::string file = dir.File("camera.yaml"), fifo = dir.File("fifo.yaml"), link = dir.File("null.yaml");
  EXPECT_TRUE(CheckOutputFree(dir.File("new.yaml"), false).ok());
  EXPECT_TRUE(CheckOutputFree("", false).ok());
  WriteTextFile(file, "old");
  const Status exists = CheckOutputFree(file, false);
  EXPECT_EQ(exists.kind(), StatusKind::kBadInput);
  EXPECT_EQ(exists.message(), file + ": exists; use --force to overwrite it");
  EXPECT_TRUE(CheckOutputFree(file, true).ok());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::filesystem::create_symlink("/dev/null", link);
  for (bool force : {false, true}) {
    EXPECT_EQ(CheckOutputFree(fifo, force).message(),
              fifo + ": not a regular file (a FIFO); hexcal replaces only files");
    EXPECT_EQ(CheckOutputFree(link, force).message(),
              link + ": not a regular file (a character device); hexcal replaces only files");
    EXPECT_EQ(CheckOutputFree(dir.path().string(), force).message(),
              dir.path().string() + ": is a directory, not a file");
  }
  // A dangling link is free: the rename replaces the link, nothing behind it.
  std::filesystem::create_symlink(dir.File("nowhere"), dir.File("dangling.yaml"));
  EXPECT_TRUE(CheckOutputFree(dir.File("dangling.yaml"), false).ok());
}

}  // namespace
}  // namespace hexcal

namespace hexcal {
namespace {

// A session file that is a symbolic link (issue 13, confinement): the write
// replaces the link with a file; the link's target is never written.
TEST(AtomicFileTest, ReplacesASymlinkAndLeavesItsTargetAlone) {
  ::hexcal::testing::TempDir dir, outside;
  const std::string target = outside.File("passwd");
  ::hexcal::testing::WriteTextFile(target, "precious");
  const std::string link = dir.File("legs.csv");
  std::filesystem::create_symlink(target, link);
  ASSERT_TRUE(WriteFileAtomically(link, "image,L1\n").ok());
  EXPECT_FALSE(std::filesystem::is_symlink(link));
  EXPECT_EQ(::hexcal::testing::ReadTextFile(link), "image,L1\n");
  EXPECT_EQ(::hexcal::testing::ReadTextFile(target), "precious");
}

}  // namespace
}  // namespace hexcal
