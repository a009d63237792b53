// Helpers for the fuzz targets: for a parser that reads a path, not bytes, the
// input is written to a file in a folder of this process's own, and the parser
// reads it from there exactly as it does in the product; for a parser with a
// writer, the round trip that every input it accepts must survive.
#pragma once
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace hexcal::fuzz {

// A fresh folder under /dev/shm (memory, so a write per input stays cheap)
// or the temp folder, removed when the process exits normally.
inline const std::string& ScratchDir() {
  static const std::string dir = [] {
    namespace fs = std::filesystem;
    const fs::path base = fs::is_directory("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
    std::string pattern = (base / "hexcal_fuzz.XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) std::abort();
    return pattern;
  }();
  static const bool cleanup_registered = [] {
    return std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(ScratchDir(), ignored);
    }) == 0;
  }();
  (void)cleanup_registered;
  return dir;
}

inline void WriteOrDie(const std::string& path, const uint8_t* data, size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) std::abort();  // the harness, not the parser, failed
}

// Text that `parse` accepts, written back by `write`, must parse again; else
// abort, which libFuzzer reports as a crash with the input.
template <typename Parse, typename Write>
void CheckRoundTrip(const uint8_t* data, size_t size, Parse parse, Write write) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto parsed = parse(text, "fuzz.yaml");
  if (!parsed.ok()) return;
  if (!parse(write(*parsed), "round-trip.yaml").ok()) std::abort();
}

}  // namespace hexcal::fuzz
