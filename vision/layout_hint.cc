#include "vision/layout_hint.h"

#include "vision/tag_family.h"

namespace hexcal {

std::optional<LayoutHint> BetterLayout(const cv::Mat& gray, const DetectorOptions& options, size_t found) {
  constexpr size_t kEnoughTags = 4;
  if (found >= kEnoughTags) return std::nullopt;
  std::optional<LayoutHint> best;
  for (const std::string& family : SupportedTagFamilies()) {
    for (int border_bits : {1, 2}) {
      if (family == options.family && border_bits == options.border_bits) continue;
      DetectorOptions other = options;
      other.family = family;
      other.border_bits = border_bits;
      other.refine_edges = false;
      StatusOr<std::unique_ptr<TagDetector>> detector = TagDetector::Create(other);
      if (!detector.ok()) continue;
      const size_t count = (*detector)->Detect(gray).tags.size();
      if (count < kEnoughTags || count <= found) continue;
      if (!best || static_cast<int>(count) > best->tags) best = LayoutHint{family, border_bits, static_cast<int>(count)};
    }
  }
  return best;
}

std::string DescribeLayoutHint(const LayoutHint& hint, const DetectorOptions& options) {
  std::string text = std::to_string(hint.tags) + " tags";
  if (hint.family != options.family) text += " of family " + hint.family;
  if (hint.border_bits != options.border_bits) text += " with border_bits " + std::to_string(hint.border_bits);
  const bool family = hint.family != options.family, border = hint.border_bits != options.border_bits;
  if (family && border) {
    text += " (the target file's family and border_bits keys)";
  } else if (family) {
    text += " (the target file's family key)";
  } else {
    text += " (--border-bits, or the target file's border_bits key)";
  }
  return text;
}

}  // namespace hexcal
