// SHA-256 (FIPS 180-4) of bytes and of files: the content hashes of a session's
// inputs and results (docs/session.md, "Results as one unit").
//
//   std::string digest = Sha256Hex("abc");  // "ba7816bf...15ad"
//   StatusOr<std::string> of_file = Sha256OfFile("legs.csv", kMaxTableBytes);
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/status.h"

namespace hexcal {

// Incremental hashing, for files read in blocks.
class Sha256 {
 public:
  Sha256();
  void Update(std::string_view bytes);
  // The digest as 64 lower-case hex digits; the object is spent afterwards.
  std::string FinishHex();

 private:
  void Compress(const uint8_t* block);

  std::array<uint32_t, 8> state_;
  std::array<uint8_t, 64> buffer_{};
  size_t buffered_ = 0;
  uint64_t total_bytes_ = 0;
};

std::string Sha256Hex(std::string_view bytes);

// Hashes a regular file (never a FIFO or device: refused at once, like
// ReadFileToString) of at most `max_bytes`, reading it in blocks.
StatusOr<std::string> Sha256OfFile(const std::string& path, size_t max_bytes);

}  // namespace hexcal
