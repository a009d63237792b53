#include "vision/target_print.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <locale>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "vision/image_codecs.h"
#include "vision/tag_family.h"

namespace hexcal {
namespace {

constexpr double kPageMarginMm = 10;
constexpr double kCaptionMm = 30;  // scale bar and three lines of text under the sheet
constexpr double kTextMm = 2.8;    // cap height of the caption
constexpr double kPointsPerMm = 72 / 25.4;

struct Rect {
  double x, y, w, h;  // mm, y up
};

// What the layout draws on: mm, origin at the page's bottom-left, y up.
class Canvas {
 public:
  virtual ~Canvas() = default;
  virtual void FillRects(const std::vector<Rect>& rects) = 0;  // one shape: their union
  virtual void StrokeRect(const Rect& rect, double line_mm) = 0;
  virtual void Text(double x, double y, const std::string& text) = 0;  // baseline at y
};

std::string Fixed(double value, int decimals) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.setf(std::ios::fixed);
  out.precision(decimals);
  out << value;
  return out.str();
}

double MmPerUnit(const Target& target) { return 1000 * MetresPerUnit(target.length_unit); }

// Size of the content (sheet and caption), mm.
std::pair<double, double> ContentSize(const Target& target) {
  const double mm = MmPerUnit(target);
  const double sheet_w = (target.Width() + 2 * target.margin) * mm,
               sheet_h = (target.Height() + 2 * target.margin) * mm;
  return {std::max(sheet_w, 120.0), sheet_h + kCaptionMm};
}

// Draws the target with its sheet's bottom-left at (x0, y0 + kCaptionMm).
void DrawTarget(const Target& target, double x0, double y0, Canvas& canvas) {
  const double mm = MmPerUnit(target);
  const double cell = target.tag_size / target.WidthAtBorder() * mm;
  const int ring = 1;  // the white ring of TagCells around the black square
  // The target frame's origin on the page: the sheet starts a margin before the tags.
  const double origin_x = x0 + (target.margin - target.TagsMin().x()) * mm;
  const double origin_y = y0 + kCaptionMm + (target.margin - target.TagsMin().y()) * mm;
  const std::vector<TagCells> tags = TagCellsOf(target.family, target.TagIds(), target.border_bits);
  for (int index = 0; index < target.NumTags(); ++index) {
    const Eigen::Vector2d o = target.TagOrigin(index) * mm;
    const TagCells& tag = tags[static_cast<size_t>(index)];
    const double top = origin_y + o.y() + target.tag_size * mm + ring * cell;
    std::vector<Rect> rects;
    for (int i = 0; i < tag.total_width; ++i) {
      for (int j = 0; j < tag.total_width;) {  // runs of black cells along the row
        if (!tag.IsBlack(i, j)) {
          ++j;
          continue;
        }
        int end = j;
        while (end < tag.total_width && tag.IsBlack(i, end)) ++end;
        rects.push_back({origin_x + o.x() + (j - ring) * cell, top - (i + 1) * cell, (end - j) * cell, cell});
        j = end;
      }
    }
    canvas.FillRects(rects);
  }
  // Scale bar: 100 mm in 10 mm steps.
  const double bar_y = y0 + kCaptionMm - 9;
  std::vector<Rect> bar;
  for (int i = 0; i < 10; i += 2) bar.push_back({x0 + i * 10.0, bar_y, 10, 3});
  canvas.FillRects(bar);
  canvas.StrokeRect({x0, bar_y, 100, 3}, 0.25);
  canvas.Text(x0 + 102, bar_y + 0.3, "100 mm");
  const std::vector<std::string> caption = TargetPrintCaption(target);
  for (size_t line = 0; line < caption.size(); ++line) canvas.Text(x0, bar_y - 6 - 5.0 * line, caption[line]);
}

// ---- PDF ------------------------------------------------------------------

std::string PdfString(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    if (c == '(' || c == ')' || c == '\\') escaped += '\\';
    escaped += c;
  }
  return "(" + escaped + ")";
}

class PdfCanvas : public Canvas {
 public:
  void FillRects(const std::vector<Rect>& rects) override {
    if (rects.empty()) return;
    for (const Rect& r : rects) content_ += Pt(r.x) + " " + Pt(r.y) + " " + Pt(r.w) + " " + Pt(r.h) + " re\n";
    content_ += "f\n";
  }
  void StrokeRect(const Rect& r, double line_mm) override {
    content_ += Pt(line_mm) + " w " + Pt(r.x) + " " + Pt(r.y) + " " + Pt(r.w) + " " + Pt(r.h) + " re S\n";
  }
  void Text(double x, double y, const std::string& text) override {
    // Helvetica's cap height is 0.718 em.
    content_ += "BT /F1 " + Fixed(kTextMm / 0.718 * kPointsPerMm, 3) + " Tf " + Pt(x) + " " + Pt(y) + " Td " +
                PdfString(text) + " Tj ET\n";
  }
  const std::string& content() const { return content_; }

 private:
  static std::string Pt(double mm) { return Fixed(mm * kPointsPerMm, 3); }
  std::string content_ = "0 g 0 G\n";
};

std::string AssemblePdf(double width_mm, double height_mm, const std::string& content) {
  std::vector<std::string> objects = {
      "<< /Type /Catalog /Pages 2 0 R /ViewerPreferences << /PrintScaling /None >> >>",
      "<< /Type /Pages /Kids [3 0 R] /Count 1 >>",
      "<< /Type /Page /Parent 2 0 R /MediaBox [0 0 " + Fixed(width_mm * kPointsPerMm, 3) + " " +
          Fixed(height_mm * kPointsPerMm, 3) + "] /Resources << /Font << /F1 4 0 R >> >> /Contents 5 0 R >>",
      "<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica /Encoding /WinAnsiEncoding >>",
      "<< /Length " + std::to_string(content.size()) + " >>\nstream\n" + content + "endstream",
      "<< /Title (hexcal calibration target) /Producer (hexcal) >>",
  };
  std::string pdf = "%PDF-1.6\n%\xE2\xE3\xCF\xD3\n";
  std::vector<size_t> offsets;
  for (size_t i = 0; i < objects.size(); ++i) {
    offsets.push_back(pdf.size());
    pdf += std::to_string(i + 1) + " 0 obj\n" + objects[i] + "\nendobj\n";
  }
  const size_t xref = pdf.size();
  pdf += "xref\n0 " + std::to_string(objects.size() + 1) + "\n0000000000 65535 f \n";
  for (size_t offset : offsets) {
    std::string number = std::to_string(offset);
    pdf += std::string(10 - number.size(), '0') + number + " 00000 n \n";
  }
  pdf += "trailer\n<< /Size " + std::to_string(objects.size() + 1) + " /Root 1 0 R /Info " +
         std::to_string(objects.size()) + " 0 R >>\nstartxref\n" + std::to_string(xref) + "\n%%EOF\n";
  return pdf;
}

// ---- PNG ------------------------------------------------------------------

class PngCanvas : public Canvas {
 public:
  PngCanvas(double width_mm, double height_mm, double dpi)
      : px_per_mm_(dpi / 25.4),
        coverage_(static_cast<int>(std::ceil(height_mm * px_per_mm_)),
                  static_cast<int>(std::ceil(width_mm * px_per_mm_)), CV_64F, cv::Scalar(0)) {}

  // Exact area coverage: each pixel adds its overlap with each rectangle.
  void FillRects(const std::vector<Rect>& rects) override {
    for (const Rect& r : rects) {
      const double x0 = r.x * px_per_mm_, x1 = (r.x + r.w) * px_per_mm_;
      const double y0 = coverage_.rows - (r.y + r.h) * px_per_mm_, y1 = coverage_.rows - r.y * px_per_mm_;
      for (int v = std::max(0, static_cast<int>(std::floor(y0)));
           v < std::min(coverage_.rows, static_cast<int>(std::ceil(y1))); ++v) {
        const double overlap_y = std::min(y1, v + 1.0) - std::max(y0, static_cast<double>(v));
        double* row = coverage_.ptr<double>(v);
        for (int u = std::max(0, static_cast<int>(std::floor(x0)));
             u < std::min(coverage_.cols, static_cast<int>(std::ceil(x1))); ++u) {
          row[u] += overlap_y * (std::min(x1, u + 1.0) - std::max(x0, static_cast<double>(u)));
        }
      }
    }
  }
  void StrokeRect(const Rect& r, double line_mm) override {
    const double t = line_mm;
    FillRects({{r.x - t / 2, r.y - t / 2, r.w + t, t},
               {r.x - t / 2, r.y + r.h - t / 2, r.w + t, t},
               {r.x - t / 2, r.y + t / 2, t, r.h - t},
               {r.x + r.w - t / 2, r.y + t / 2, t, r.h - t}});
  }
  void Text(double x, double y, const std::string& text) override { texts_.push_back({x, y, text}); }

  cv::Mat Render() const {
    cv::Mat grey;
    cv::Mat clipped = cv::min(coverage_, 1.0);
    clipped.convertTo(grey, CV_8U, -255, 255);
    int baseline = 0;
    const double scale = kTextMm * px_per_mm_ / cv::getTextSize("H", cv::FONT_HERSHEY_SIMPLEX, 1, 1, &baseline).height;
    const int thickness = std::max(1, static_cast<int>(std::lround(scale * 1.5)));
    for (const auto& [x, y, text] : texts_) {
      cv::putText(grey, text, {cvRound(x * px_per_mm_), cvRound(coverage_.rows - y * px_per_mm_)},
                  cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0), thickness, cv::LINE_AA);
    }
    return grey;
  }

 private:
  struct PlacedText {
    double x, y;
    std::string text;
  };
  double px_per_mm_;
  cv::Mat coverage_;  // black ink fraction per pixel
  std::vector<PlacedText> texts_;
};

uint32_t Crc32(const std::string& bytes) {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t n = 0; n < 256; ++n) {
      uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  uint32_t crc = 0xFFFFFFFFu;
  for (unsigned char byte : bytes) crc = table[(crc ^ byte) & 0xFF] ^ (crc >> 8);
  return crc ^ 0xFFFFFFFFu;
}

std::string BigEndian(uint32_t value) {
  return {static_cast<char>(value >> 24), static_cast<char>(value >> 16), static_cast<char>(value >> 8),
          static_cast<char>(value)};
}

// A pHYs chunk (pixels per metre) inserted after IHDR, which OpenCV does not write.
std::string WithResolution(const std::string& png, double dpi) {
  const uint32_t per_metre = static_cast<uint32_t>(std::lround(dpi / 0.0254));
  const std::string body = "pHYs" + BigEndian(per_metre) + BigEndian(per_metre) + std::string(1, '\x01');
  const std::string chunk = BigEndian(9) + body + BigEndian(Crc32(body));
  constexpr size_t kAfterHeader = 8 + 25;  // signature, IHDR
  return png.substr(0, kAfterHeader) + chunk + png.substr(kAfterHeader);
}

// Where the target frame's origin is on the print.
std::string OriginCaption(const Target& target) {
  if (target.Layout() == TargetLayout::kTagList) {
    const Eigen::Vector2d o = target.TagOrigin(0);
    return "tag " + std::to_string(target.TagId(0)) + "'s bottom-left corner at x " + FormatNumber(o.x()) + ", y " +
           FormatNumber(o.y()) + " " + LengthUnitName(target.length_unit);
  }
  // A grid's index 0 is the bottom-left cell's tag, if that cell has one.
  if (target.NumTags() > 0 && target.TagOrigin(0).isZero()) {
    return "origin at the outer bottom-left corner of tag " + std::to_string(target.TagId(0));
  }
  return "origin at the bottom-left corner of the grid's bottom-left cell (no tag there)";
}

}  // namespace

std::vector<std::string> TargetPrintCaption(const Target& target) {
  const double mm = MmPerUnit(target);
  std::ostringstream size;
  size.imbue(std::locale::classic());
  size.precision(6);
  size << target.tag_size * mm;
  return {"hexcal target: " + DescribeTarget(target),
          "Print at 100 % (no scaling, no fit to page). Check: the bar is 100 mm, a tag's black square " + size.str() +
              " mm.",
          "Target frame: " + OriginCaption(target) + ", x to the right, y up, z out of the page."};
}

PrintSheet TargetPdfSheet(const Target& target) {
  const auto [content_w, content_h] = ContentSize(target);
  const double need_w = content_w + 2 * kPageMarginMm, need_h = content_h + 2 * kPageMarginMm;
  constexpr std::array<std::array<double, 2>, 5> kSizes = {
      {{210, 297}, {297, 420}, {420, 594}, {594, 841}, {841, 1189}}};
  for (size_t a = 0; a < kSizes.size(); ++a) {
    const auto [short_side, long_side] = kSizes[a];
    const std::string name = "A" + std::to_string(4 - static_cast<int>(a));
    if (need_w <= short_side && need_h <= long_side) return {short_side, long_side, name + " portrait"};
    if (need_w <= long_side && need_h <= short_side) return {long_side, short_side, name + " landscape"};
  }
  return {need_w, need_h, "custom"};
}

std::string DescribeSheet(const PrintSheet& sheet) {
  return sheet.name + " (" + Fixed(sheet.width_mm, 0) + " x " + Fixed(sheet.height_mm, 0) + " mm)";
}

std::string TargetPdf(const Target& target) {
  const auto [content_w, content_h] = ContentSize(target);
  const PrintSheet sheet = TargetPdfSheet(target);
  PdfCanvas canvas;
  DrawTarget(target, (sheet.width_mm - content_w) / 2, (sheet.height_mm - content_h) / 2, canvas);
  return AssemblePdf(sheet.width_mm, sheet.height_mm, canvas.content());
}

const OptionTable<TargetPrintOptions>& TargetPrintOptionSpecs() {
  static const OptionTable<TargetPrintOptions> table = {NumberOption<TargetPrintOptions>(
      "dpi", "PNG resolution", OptionType::kNumber, "dpi", 50, 1200, "resolution of a PNG print (a PDF is vector)",
      [](TargetPrintOptions& o) -> double& { return o.dpi; })};
  return table;
}

StatusOr<std::string> TargetPng(const Target& target, double dpi) {
  if (Status s = CheckOptionRanges(TargetPrintOptionSpecs(), TargetPrintOptions{dpi}); !s.ok()) return s;
  const auto [content_w, content_h] = ContentSize(target);
  const double page_w = content_w + 2 * kPageMarginMm, page_h = content_h + 2 * kPageMarginMm;
  if (std::max(page_w, page_h) * dpi / 25.4 > 30000) {
    return Status::BadOption(
        "dpi", "the PNG would be over 30000 pixels on a side at " + Fixed(dpi, 0) + " dpi; choose a lower one");
  }
  PngCanvas canvas(page_w, page_h, dpi);
  DrawTarget(target, kPageMarginMm, kPageMarginMm, canvas);
  StatusOr<std::string> bytes = EncodePng(canvas.Render());
  if (!bytes.ok()) return bytes.status();
  return WithResolution(*bytes, dpi);
}

Status WriteTargetPrint(const Target& target, const std::string& path, double dpi) {
  std::string extension = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".pdf") return WriteFileAtomically(path, TargetPdf(target));
  if (extension != ".png") return Status::BadInput(path + ": the output must end in .pdf or .png");
  StatusOr<std::string> png = TargetPng(target, dpi);
  if (!png.ok()) return png.status();
  return WriteFileAtomically(path, *png);
}

}  // namespace hexcal
