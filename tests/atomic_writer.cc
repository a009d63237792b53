// atomic_writer: the victim and the judge of the kill -9 test
// (tests/atomic_kill.sh, docs/hardening.md).
//
//   atomic_writer write FILE MEGABYTES FIRST [COUNT]
//                                                rewrite FILE with generation FIRST,
//                                                FIRST+1, ... through WriteFileAtomically,
//                                                printing "wrote N" after each one returns;
//                                                COUNT stops it (default: forever)
//   atomic_writer check FILE                     print "generation N" if FILE is one
//                                                complete generation, else exit 1
//
// A generation is a header line "generation N", MEGABYTES MiB of lines that all
// carry N, and a last line "fnv1a64 HEX" with the FNV-1a hash of everything
// before it. A torn, truncated or mixed file fails the hash or the per-line check.
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

#include "core/atomic_file.h"

namespace {

constexpr size_t kLineLength = 64;  // bytes per body line, newline included

uint64_t Fnv1a64(const char* data, size_t size) {
  uint64_t hash = 14695981039346656037ull;
  for (size_t i = 0; i < size; ++i) {
    hash ^= static_cast<unsigned char>(data[i]);
    hash *= 1099511628211ull;
  }
  return hash;
}

std::string BodyLine(long generation) {
  char prefix[32];
  std::snprintf(prefix, sizeof(prefix), "g%020ld ", generation);
  std::string line(prefix);
  line.resize(kLineLength - 1, 'x');
  line.push_back('\n');
  return line;
}

std::string Generation(long generation, size_t megabytes) {
  std::string text = "generation " + std::to_string(generation) + "\n";
  const std::string line = BodyLine(generation);
  const size_t lines = megabytes * (1u << 20) / kLineLength;
  text.reserve(text.size() + lines * kLineLength + 32);
  for (size_t i = 0; i < lines; ++i) text += line;
  char checksum[40];
  std::snprintf(checksum, sizeof(checksum), "fnv1a64 %016" PRIx64 "\n", Fnv1a64(text.data(), text.size()));
  return text + checksum;
}

int Write(const std::string& path, size_t megabytes, long first, long count) {
  for (long generation = first; count <= 0 || generation < first + count; ++generation) {
    const hexcal::Status written = hexcal::WriteFileAtomically(path, Generation(generation, megabytes));
    if (!written.ok()) {
      std::cerr << written.message() << "\n";
      return 1;
    }
    std::cout << "wrote " << generation << std::endl;  // flushed: the test reads it after SIGKILL
  }
  return 0;
}

int Check(const std::string& path) {
  const hexcal::StatusOr<std::string> read = hexcal::ReadFileToString(path, 64 * hexcal::kMiB);
  if (!read.ok()) {
    std::cerr << read.status().message() << "\n";
    return 1;
  }
  const std::string& text = *read;
  long generation = 0;
  if (std::sscanf(text.c_str(), "generation %ld\n", &generation) != 1 || generation < 1) {
    std::cerr << path << ": no 'generation N' header\n";
    return 1;
  }
  const size_t checksum_start = text.rfind("fnv1a64 ");
  uint64_t stored = 0;
  if (checksum_start == std::string::npos ||
      std::sscanf(text.c_str() + checksum_start, "fnv1a64 %" SCNx64, &stored) != 1 || text.back() != '\n' ||
      text.find('\n', checksum_start) != text.size() - 1) {
    std::cerr << path << ": no final checksum line\n";
    return 1;
  }
  if (Fnv1a64(text.data(), checksum_start) != stored) {
    std::cerr << path << ": checksum mismatch\n";
    return 1;
  }
  const size_t body_start = text.find('\n') + 1;
  const std::string line = BodyLine(generation);
  if ((checksum_start - body_start) % kLineLength != 0) {
    std::cerr << path << ": body is not whole lines\n";
    return 1;
  }
  for (size_t at = body_start; at < checksum_start; at += kLineLength) {
    if (text.compare(at, kLineLength, line) != 0) {
      std::cerr << path << ": body line at byte " << at << " is not from generation " << generation << "\n";
      return 1;
    }
  }
  std::cout << "generation " << generation << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "write" && (argc == 5 || argc == 6)) {
    const long first = std::strtol(argv[4], nullptr, 10);
    if (first < 1) return 2;
    return Write(argv[2], std::strtoul(argv[3], nullptr, 10), first, argc == 6 ? std::strtol(argv[5], nullptr, 10) : 0);
  }
  if (mode == "check" && argc == 3) return Check(argv[2]);
  std::cerr << "usage: atomic_writer write FILE MEGABYTES FIRST [COUNT] | atomic_writer check FILE\n";
  return 2;
}
