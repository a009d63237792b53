#include "vision/image_file.h"

#include <locale>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <vector>

#include "core/atomic_file.h"
#include "vision/image_codecs.h"
#include "vision/image_header.h"

namespace hexcal {
namespace {

// The checks made on the header before decoding; OK when the decoder may run.
Status CheckImageHeader(const ImageHeader& header, const std::string& source) {
  // imdecode tries every decoder OpenCV was built with (on Debian also DICOM,
  // JPEG 2000, OpenEXR, WebP ...), and some abort the process on a bad file
  // (GDCM's reader asserts: found by fuzz/image_fuzz). hexcal reads only
  // PNG, JPEG and TIFF, so nothing else reaches imdecode.
  if (header.format == ImageFormat::kOther) {
    return Status::BadInput(source + ": cannot decode: not a PNG, JPEG or TIFF file");
  }
  // Truncated files are caught here, before the decoders print their own
  // complaints on stderr.
  if (header.truncated && header.format == ImageFormat::kPng) {
    return Status::BadInput(source + ": truncated PNG (no IEND chunk)");
  }
  if (header.truncated) return Status::BadInput(source + ": truncated JPEG (no end-of-image marker)");
  if (!header.corrupt.empty())
    return Status::BadInput(source + ": cannot decode: corrupt JPEG (" + header.corrupt + ")");
  // The decoder allocates what the header claims, however small the file.
  if (header.size && header.size->Pixels() > kMaxImagePixels) {
    return Status::BadInput(source + ": " + std::to_string(header.size->width) + " x " +
                            std::to_string(header.size->height) + " pixels is over the " +
                            std::to_string(kMaxImagePixels / 1'000'000) + "-megapixel limit");
  }
  return Status::Ok();
}


// Grey in the file's own depth: colour weighted, alpha over white.
cv::Mat ToGrey(const cv::Mat& decoded) {
  const int channels = decoded.channels();
  if (channels == 1) return decoded;
  const double white = decoded.depth() == CV_8U ? 255 : decoded.depth() == CV_16U ? 65535 : 1;
  cv::Mat grey, alpha;
  if (channels == 2) {
    cv::extractChannel(decoded, grey, 0);
  } else {
    cv::cvtColor(decoded, grey, channels == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  }
  if (channels == 3) return grey;
  cv::extractChannel(decoded, alpha, channels - 1);
  double transparent = 0;
  cv::minMaxLoc(alpha, &transparent);
  if (transparent >= white) return grey;  // opaque everywhere
  // grey · α + white · (1 − α)
  cv::Mat g;
  grey.convertTo(g, CV_32F);
  alpha.convertTo(alpha, CV_32F, 1.0 / white);
  cv::Mat composite = g.mul(alpha) + white * (1.0 - alpha);
  composite.convertTo(grey, decoded.depth());
  return grey;
}

// 8-bit grey; deeper images scaled so that their range fills 0-255.
cv::Mat ToEightBit(const cv::Mat& grey, ImageNotes* notes) {
  if (grey.depth() == CV_8U) return grey;
  double low = 0, high = 0;
  cv::minMaxLoc(grey, &low, &high);
  notes->range_low = low;
  notes->range_high = high;
  cv::Mat eight;
  const double scale = high > low ? 255.0 / (high - low) : 0;
  grey.convertTo(eight, CV_8U, scale, -low * scale);
  return eight;
}

int BitsOf(int depth) {
  switch (depth) {
    case CV_8U: return 8;
    case CV_16U: return 16;
    default: return 32;
  }
}

}  // namespace

StatusOr<cv::Mat> LoadGrayImage(const std::string& path, ImageNotes* notes) {
  StatusOr<std::string> bytes = ReadFileToString(path, kMaxImageBytes);
  if (!bytes.ok()) return bytes.status();
  return DecodeGrayImage(*bytes, path, notes);
}

StatusOr<cv::Mat> DecodeGrayImage(const std::string& bytes, const std::string& source, ImageNotes* notes) {
  if (bytes.empty()) return Status::BadInput(source + ": empty file");
  const ImageHeader header = ReadImageHeader(bytes);
  if (const Status checked = CheckImageHeader(header, source); !checked.ok()) return checked;
  // Every channel and bit as stored, orientation not applied.
  StatusOr<cv::Mat> image = DecodeImage(bytes);
  if (!image.ok()) return Status(image.status()).Prefixed(source + ": ");
  const cv::Mat& decoded = *image;
  if (decoded.channels() > 4 || (decoded.depth() != CV_8U && decoded.depth() != CV_16U && decoded.depth() != CV_32F)) {
    return Status::BadInput(source + ": cannot decode: " + std::to_string(decoded.channels()) +
                            " channels of an unsupported sample type (8-bit, 16-bit or float grey or colour are read)");
  }
  ImageNotes local;
  ImageNotes* out = notes ? notes : &local;
  *out = ImageNotes{BitsOf(decoded.depth()), decoded.channels(), header.orientation, 0, 255};
  return ToEightBit(ToGrey(decoded), out);
}

std::string DescribeImageNotes(const ImageNotes& notes) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  if (notes.bits > 8) {
    out << notes.bits << "-bit, grey " << notes.range_low << "-" << notes.range_high << " scaled to 0-255";
  }
  if (notes.orientation != 1) {
    out << (out.tellp() > 0 ? "; " : "") << "EXIF orientation " << notes.orientation
        << " not applied (pixels as stored)";
  }
  return out.str();
}

}  // namespace hexcal
