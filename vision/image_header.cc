#include "vision/image_header.h"

#include <algorithm>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <map>

namespace hexcal {
namespace {

constexpr uint64_t kNone = std::numeric_limits<uint64_t>::max();

uint8_t ByteAt(std::string_view bytes, uint64_t offset) { return static_cast<uint8_t>(bytes[offset]); }

// The unsigned integer of `width` bytes at `offset`, or nothing if the file
// ends first; `offset` may be any number read from the file.
std::optional<uint64_t> ReadUint(std::string_view bytes, uint64_t offset, int width, bool big_endian) {
  const uint64_t size = bytes.size();
  if (offset > size || size - offset < static_cast<uint64_t>(width)) return std::nullopt;
  uint64_t value = 0;
  for (int i = 0; i < width; ++i) {
    value = (value << 8) | ByteAt(bytes, offset + static_cast<uint64_t>(big_endian ? i : width - 1 - i));
  }
  return value;
}

std::string Hex(uint8_t code) {
  static const char kDigits[] = "0123456789ABCDEF";
  return std::string{kDigits[code >> 4], kDigits[code & 15]};
}

// ---- TIFF (TIFF 6.0 section 2; BigTIFF: libtiff's extension, magic 43) ----

struct TiffLayout {
  bool big_endian = false;
  int offset_bytes = 4;  // an IFD entry's count and value field: 4, or 8 in BigTIFF
  int count_bytes = 2;   // the IFD's number of entries: 2, or 8 in BigTIFF
  uint64_t first_ifd = 0;
  int EntryBytes() const { return 4 + 2 * offset_bytes; }  // tag, type, count, value
};

std::optional<TiffLayout> ReadTiffLayout(std::string_view bytes) {
  TiffLayout layout;
  if (bytes.substr(0, 2) == "MM") {
    layout.big_endian = true;
  } else if (bytes.substr(0, 2) != "II") {
    return std::nullopt;
  }
  const std::optional<uint64_t> magic = ReadUint(bytes, 2, 2, layout.big_endian);
  if (magic == 42u) {
    const std::optional<uint64_t> ifd = ReadUint(bytes, 4, 4, layout.big_endian);
    if (!ifd) return std::nullopt;
    layout.first_ifd = *ifd;
    return layout;
  }
  // BigTIFF: the offset size (8) and a zero word, then an 8-byte offset.
  if (magic != 43u || ReadUint(bytes, 4, 2, layout.big_endian) != 8u ||
      ReadUint(bytes, 6, 2, layout.big_endian) != 0u) {
    return std::nullopt;
  }
  const std::optional<uint64_t> ifd = ReadUint(bytes, 8, 8, layout.big_endian);
  if (!ifd) return std::nullopt;
  layout = TiffLayout{layout.big_endian, 8, 8, *ifd};
  return layout;
}

// The number in an entry holding one SHORT (3), LONG (4) or LONG8 (16); a value
// that fits the entry's value field is stored there, left-justified.
std::optional<uint64_t> ReadTiffEntryNumber(std::string_view bytes, uint64_t entry, const TiffLayout& layout) {
  const std::optional<uint64_t> type = ReadUint(bytes, entry + 2, 2, layout.big_endian);
  const std::optional<uint64_t> count = ReadUint(bytes, entry + 4, layout.offset_bytes, layout.big_endian);
  if (!type || count != 1u) return std::nullopt;
  const int width = *type == 3 ? 2 : *type == 4 ? 4 : *type == 16 ? 8 : 0;
  if (width == 0 || width > layout.offset_bytes) return std::nullopt;
  return ReadUint(bytes, entry + 4 + static_cast<uint64_t>(layout.offset_bytes), width, layout.big_endian);
}

// ---- JPEG (ITU-T T.81 annex B) ----

// The offset of the next marker's FF at or after `pos`, skipping what a
// decoder skips (libjpeg's next_marker): bytes other than FF (entropy-coded
// data, or stray bytes between segments), fill bytes (FF FF ...), stuffed zeros
// (FF 00) and restart markers (FF D0-D7). kNone if the file ends first.
uint64_t NextJpegMarker(std::string_view bytes, uint64_t pos) {
  const uint64_t size = bytes.size();
  while (pos < size) {
    const void* ff = std::memchr(bytes.data() + pos, 0xFF, size - pos);
    if (ff == nullptr) return kNone;
    pos = static_cast<uint64_t>(static_cast<const char*>(ff) - bytes.data());
    while (pos + 1 < size && ByteAt(bytes, pos + 1) == 0xFF) ++pos;
    if (pos + 1 >= size) return kNone;
    const uint8_t code = ByteAt(bytes, pos + 1);
    if (code != 0x00 && (code < 0xD0 || code > 0xD7)) return pos;
    pos += 2;
  }
  return kNone;
}

// SOF0-SOF15 except DHT (C4), JPG (C8) and DAC (CC), which share the range.
bool IsStartOfFrame(uint8_t code) {
  return code >= 0xC0 && code <= 0xCF && code != 0xC4 && code != 0xC8 && code != 0xCC;
}

// Reads the segment of marker `code` whose length field is at `pos` (already
// known to lie inside the file) into `layout`; false with layout.corrupt set
// when a decoder would stop here.
bool ReadJpegSegment(std::string_view bytes, uint8_t code, uint64_t pos, uint64_t length, bool* seen_scan,
                     JpegLayout* layout) {
  auto where = [&] { return "marker FF" + Hex(code) + " at byte " + std::to_string(pos - 2); };
  if (length < 2) {
    layout->corrupt = where() + " has length " + std::to_string(length);
    return false;
  }
  if (IsStartOfFrame(code)) {
    // Length, precision (1 byte), height, width, number of components (1 byte).
    if (layout->size) layout->corrupt = where() + " is a second frame header";
    if (length < 8) layout->corrupt = where() + " is a frame header of " + std::to_string(length) + " bytes";
    if (!layout->corrupt.empty()) return false;
    layout->size = PixelSize{*ReadUint(bytes, pos + 5, 2, true), *ReadUint(bytes, pos + 3, 2, true)};
  } else if (code == 0xE1 && length >= 8 && bytes.substr(pos + 2, 6) == std::string_view("Exif\0\0", 6)) {
    // APP1 EXIF: a TIFF structure whose IFD0 may hold the orientation.
    layout->orientation = ReadTiffOrientation(bytes.substr(pos + 8, length - 8));
  } else if (code == 0xDA) {
    if (!layout->size) {
      layout->corrupt = where() + " starts a scan before the frame header";
      return false;
    }
    *seen_scan = true;
  }
  return true;
}

}  // namespace

uint64_t PixelSize::Pixels() const {
  if (width != 0 && height > std::numeric_limits<uint64_t>::max() / width) return std::numeric_limits<uint64_t>::max();
  return width * height;
}

ImageFormat SniffImageFormat(std::string_view bytes) {
  static constexpr std::string_view kTiffSignatures[] = {std::string_view("II*\0", 4), std::string_view("MM\0*", 4),
                                                         std::string_view("II+\0", 4), std::string_view("MM\0+", 4)};
  if (bytes.substr(0, 8) == std::string_view("\x89PNG\r\n\x1a\n", 8)) return ImageFormat::kPng;
  if (bytes.substr(0, 3) == "\xFF\xD8\xFF") return ImageFormat::kJpeg;
  for (std::string_view signature : kTiffSignatures) {
    if (bytes.substr(0, 4) == signature) return ImageFormat::kTiff;
  }
  return ImageFormat::kOther;
}

std::optional<PixelSize> ReadPngSize(std::string_view bytes) {
  // Signature (8), then the IHDR chunk: length 13, "IHDR", width, height, ...
  if (SniffImageFormat(bytes) != ImageFormat::kPng || ReadUint(bytes, 8, 4, true) != 13u ||
      bytes.substr(12, 4) != "IHDR") {
    return std::nullopt;
  }
  const std::optional<uint64_t> width = ReadUint(bytes, 16, 4, true);
  const std::optional<uint64_t> height = ReadUint(bytes, 20, 4, true);
  if (!width || !height) return std::nullopt;
  return PixelSize{*width, *height};
}

namespace {

// The numbers of `tags` in the first IFD, where present.
std::map<uint64_t, uint64_t> ReadTiffFirstIfd(std::string_view bytes, std::initializer_list<uint64_t> tags) {
  std::map<uint64_t, uint64_t> found;
  const std::optional<TiffLayout> layout = ReadTiffLayout(bytes);
  if (!layout) return found;
  const std::optional<uint64_t> count = ReadUint(bytes, layout->first_ifd, layout->count_bytes, layout->big_endian);
  if (!count) return found;
  const uint64_t first_entry = layout->first_ifd + static_cast<uint64_t>(layout->count_bytes);
  const uint64_t entry_bytes = static_cast<uint64_t>(layout->EntryBytes());
  // The count is the file's word: stop at the end of the file, whatever it says.
  for (uint64_t i = 0; i < *count; ++i) {
    const uint64_t entry = first_entry + i * entry_bytes;
    if (entry > bytes.size() || bytes.size() - entry < entry_bytes) break;
    const uint64_t tag = *ReadUint(bytes, entry, 2, layout->big_endian);
    if (std::find(tags.begin(), tags.end(), tag) == tags.end()) continue;
    if (const std::optional<uint64_t> value = ReadTiffEntryNumber(bytes, entry, *layout)) found[tag] = *value;
  }
  return found;
}

constexpr uint64_t kTiffWidth = 256, kTiffHeight = 257, kTiffOrientation = 274;

}  // namespace

std::optional<PixelSize> ReadTiffSize(std::string_view bytes) {
  const std::map<uint64_t, uint64_t> numbers = ReadTiffFirstIfd(bytes, {kTiffWidth, kTiffHeight});
  if (numbers.size() != 2) return std::nullopt;
  return PixelSize{numbers.at(kTiffWidth), numbers.at(kTiffHeight)};
}

int ReadTiffOrientation(std::string_view bytes) {
  const std::map<uint64_t, uint64_t> numbers = ReadTiffFirstIfd(bytes, {kTiffOrientation});
  const auto it = numbers.find(kTiffOrientation);
  return it != numbers.end() && it->second >= 1 && it->second <= 8 ? static_cast<int>(it->second) : 1;
}

JpegLayout WalkJpeg(std::string_view bytes) {
  JpegLayout layout;
  if (bytes.substr(0, 2) != "\xFF\xD8") {
    layout.corrupt = "no start-of-image marker";
    return layout;
  }
  bool seen_scan = false;
  uint64_t pos = 2;
  for (;;) {
    const uint64_t marker = NextJpegMarker(bytes, pos);
    if (marker == kNone) return layout;  // the file ends before the image: truncated
    const uint8_t code = ByteAt(bytes, marker + 1);
    pos = marker + 2;
    if (code == 0xD9) {  // EOI
      if (!seen_scan) layout.corrupt = "end-of-image marker at byte " + std::to_string(marker) + " before any scan";
      layout.complete = seen_scan;
      layout.end = pos;
      return layout;
    }
    if (code == 0xD8) {
      layout.corrupt = "a second start-of-image marker at byte " + std::to_string(marker);
      return layout;
    }
    if (code == 0x01) continue;  // TEM: a marker without a segment
    const std::optional<uint64_t> length = ReadUint(bytes, pos, 2, true);
    if (!length || *length > bytes.size() - pos) return layout;  // truncated inside the segment
    if (!ReadJpegSegment(bytes, code, pos, *length, &seen_scan, &layout)) return layout;
    pos += *length;
  }
}

ImageHeader ReadImageHeader(std::string_view bytes) {
  ImageHeader header;
  header.format = SniffImageFormat(bytes);
  switch (header.format) {
    case ImageFormat::kPng:
      header.size = ReadPngSize(bytes);
      // IEND is the last chunk (12 bytes); a little slack for writers that pad.
      header.truncated = bytes.find("IEND", bytes.size() > 64 ? bytes.size() - 64 : 0) == std::string_view::npos;
      break;
    case ImageFormat::kJpeg: {
      JpegLayout layout = WalkJpeg(bytes);
      header.size = layout.size;
      header.truncated = !layout.complete && layout.corrupt.empty();
      header.corrupt = std::move(layout.corrupt);
      header.orientation = layout.orientation;
      break;
    }
    case ImageFormat::kTiff:
      // A TIFF whose first IFD cannot be read here has no size: OpenCV's
      // decoder then decides (libtiff refuses such a file; OpenCV's own
      // limit, 2^30 pixels, bounds the rest).
      header.size = ReadTiffSize(bytes);
      header.orientation = ReadTiffOrientation(bytes);
      break;
    case ImageFormat::kOther:
      break;
  }
  return header;
}

}  // namespace hexcal
