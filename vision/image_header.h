// What an image file says about itself before it is decoded: its format,
// whether it is complete, and its width and height.
//
// DecodeGrayImage (vision/detection.h) reads this first so that a small file
// cannot make the decoder allocate a huge image (a 30 KB PNG of zeros whose
// IHDR claims 30000 x 30000 would decode into 900 MB) and so that a truncated
// file is refused before the decoder prints its own complaints. Every offset
// and length comes from the file and is checked against its size before use;
// a header that cannot be read gives no size, never a guess.
//
//   const ImageHeader header = ReadImageHeader(bytes);
//   if (header.size && header.size->Pixels() > kMaxImagePixels) { /* refuse */ }
//
// JPEG is read as a decoder reads it (ITU-T T.81 annex B): the marker segments
// in order, skipped by their lengths (so an EXIF thumbnail's own SOI/EOI inside
// APP1 is never seen), the size from the SOFn frame header, then the
// entropy-coded data of each scan up to the next marker (FF 00 is a stuffed
// byte, FF D0-D7 a restart marker) until the primary image's end-of-image
// marker. Anything after it (a phone's gain map or MPF images) is not read.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace hexcal {

// Images larger than this are refused before decoding. A 108-MP phone photo
// (12000 x 9000) and a print-resolution chart (10482 x 8268, 86.7 MP) pass.
// Detection peaks at about 11 bytes per pixel (measured: 995 MB on the 86.7-MP
// chart), so 150 MP is about 1.7 GB per image being measured at once.
constexpr uint64_t kMaxImagePixels = 150'000'000;

enum class ImageFormat { kOther, kPng, kJpeg, kTiff };

struct PixelSize {
  uint64_t width = 0;       // pixels
  uint64_t height = 0;      // pixels
  uint64_t Pixels() const;  // width · height, saturating at UINT64_MAX
};

// The file's shape as far as its header tells it.
struct ImageHeader {
  ImageFormat format = ImageFormat::kOther;
  std::optional<PixelSize> size;  // none when the header cannot be read
  bool truncated = false;         // the file ends before the image does (PNG, JPEG)
  std::string corrupt;            // why the structure cannot be decoded (JPEG), or empty
  int orientation = 1;            // EXIF / TIFF Orientation, 1-8 (1: as stored); never applied
};

// By its signature: PNG, JPEG (SOI and a marker), TIFF or BigTIFF.
ImageFormat SniffImageFormat(std::string_view bytes);

// The size in the IHDR chunk, which a PNG must start with.
std::optional<PixelSize> ReadPngSize(std::string_view bytes);

// ImageWidth (256) and ImageLength (257) of the first IFD, the page a decoder
// reads: TIFF and BigTIFF, little- ("II") and big-endian ("MM"), SHORT, LONG or
// LONG8 values.
std::optional<PixelSize> ReadTiffSize(std::string_view bytes);

// The Orientation tag (274) of the first IFD of a TIFF structure (a TIFF file,
// or a JPEG's EXIF block): 1-8, and 1 when absent or out of range.
int ReadTiffOrientation(std::string_view bytes);

// The marker walk described above.
struct JpegLayout {
  std::optional<PixelSize> size;  // from the SOFn frame header
  bool complete = false;          // the primary image's EOI was reached
  uint64_t end = 0;               // offset just past that EOI
  std::string corrupt;            // a structure no decoder accepts, or empty
  int orientation = 1;            // from an EXIF APP1 segment, 1-8
};
JpegLayout WalkJpeg(std::string_view bytes);

// All of the above for the file's format.
ImageHeader ReadImageHeader(std::string_view bytes);

}  // namespace hexcal
