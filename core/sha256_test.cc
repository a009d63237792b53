#include "core/sha256.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "core/atomic_file.h"
#include "tests/test_support.h"

namespace hexcal {
namespace {

using ::hexcal::testing::ReadTextFile;
using ::hexcal::testing::TempDir;
using ::hexcal::testing::WriteTextFile;

// FIPS 180-4 examples (NIST CSRC "Examples with intermediate values").
TEST(Sha256, MatchesTheNistExamples) {
  EXPECT_EQ(Sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(Sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(Sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(Sha256Hex(std::string(1000000, 'a')), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, IncrementalEqualsWholeAtEveryBlockBoundary) {
  std::string text;
  for (int i = 0; i < 300; ++i) text.push_back(static_cast<char>('a' + i % 26));
  for (size_t split : {0, 1, 55, 56, 63, 64, 65, 128, 299}) {
    Sha256 hash;
    hash.Update(std::string_view(text).substr(0, split));
    hash.Update(std::string_view(text).substr(split));
    EXPECT_EQ(hash.FinishHex(), Sha256Hex(text)) << split;
  }
}

TEST(Sha256, OfAFileEqualsOfItsBytesAndRefusesFifosAndBigFiles) {
  TempDir dir;
  const std::string path = dir.File("legs.csv");
  const std::string text(200000, 'x');
  WriteTextFile(path, text);
  StatusOr<std::string> hash = Sha256OfFile(path, kMaxTableBytes);
  ASSERT_TRUE(hash.ok()) << hash.status().message();
  EXPECT_EQ(*hash, Sha256Hex(text));
  EXPECT_NE(Sha256OfFile(path, 1000).status().message().find(": 0.2 MiB is over the"), std::string::npos);
  const std::string fifo = dir.File("fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(Sha256OfFile(fifo, kMaxTableBytes).status().message().find("not a regular file"), std::string::npos);
  EXPECT_FALSE(Sha256OfFile(dir.File("missing"), kMaxTableBytes).ok());
}

}  // namespace
}  // namespace hexcal
