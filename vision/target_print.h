// Printable targets at exact scale, with a 100 mm scale bar and the target's
// parameters printed under it, so a print can be checked with a ruler.
//
// PDF: one page of the smallest ISO A size (A4 .. A0, either orientation) that
// holds the sheet plus 10 mm of printer margin; tags as filled rectangles
// (one path per tag, so no hairline seams), text in Helvetica, and
// /PrintScaling /None so that viewers print at 100 %.
// PNG: 8-bit grey at `dpi`, edges anti-aliased by exact area coverage, with
// the resolution recorded in a pHYs chunk so that image tools print it to scale.
//
//   Status written = WriteTargetPrint(target, "target.pdf", /*dpi=*/300);
#pragma once

#include <string>

#include "core/option_spec.h"
#include "core/status.h"
#include "vision/target.h"

namespace hexcal {

// The PDF's sheet: the smallest ISO A size holding the target and the
// printer margin, turned to fit; wider than A0, the content's own size.
struct PrintSheet {
  double width_mm = 0, height_mm = 0;
  std::string name;  // "A3 portrait", or "custom" beyond A0
};
PrintSheet TargetPdfSheet(const Target& target);
// "A3 portrait (297 x 420 mm)": what to load into the printer.
std::string DescribeSheet(const PrintSheet& sheet);

// PDF file bytes, on TargetPdfSheet(target).
std::string TargetPdf(const Target& target);
// PNG file bytes; error (naming the option `dpi`) if dpi is outside its range
// (TargetPrintOptionSpecs) or the image would exceed 30000 px on a side.
StatusOr<std::string> TargetPng(const Target& target, double dpi);
// By the extension of `path` (.pdf or .png, any case), written atomically.
Status WriteTargetPrint(const Target& target, const std::string& path, double dpi);

// How a target is printed: the PNG's resolution. Its descriptor holds the
// one range WriteTargetPrint takes and `target print --dpi` and its help
// show (the help said [30 - 2400], issue 36).
struct TargetPrintOptions {
  double dpi = 300;  // PNG resolution, dots per inch (a PDF is vector)
};
const OptionTable<TargetPrintOptions>& TargetPrintOptionSpecs();

// Lines printed under the target (also in the PDF).
std::vector<std::string> TargetPrintCaption(const Target& target);

}  // namespace hexcal
