#include "workflow/board_pose_shortfall.h"

#include <filesystem>
#include <vector>

#include "core/session.h"
#include "vision/image_file.h"
#include "vision/layout_hint.h"

namespace hexcal::workflow {
namespace {

constexpr size_t kNamesShown = 3;

// "no_target 12 (view_0000.png, view_0001.png, view_0002.png, …)"
std::string StatusCounts(const std::map<std::string, std::vector<std::string>>& by_status) {
  std::string text;
  for (const auto& [status, images] : by_status) {
    if (!text.empty()) text += "; ";
    text += status + " " + std::to_string(images.size()) + " (";
    for (size_t i = 0; i < images.size() && i < kNamesShown; ++i) text += (i ? ", " : "") + images[i];
    text += images.size() > kNamesShown ? ", …)" : ")";
  }
  return text;
}

// What the image holds when not the target's tags.
std::string WhatTheImageHolds(const std::string& dir, const std::string& image, const Target& target) {
  StatusOr<cv::Mat> gray = LoadGrayImage((std::filesystem::path(SessionPaths(dir).images) / image).string());
  if (!gray.ok()) return image + " cannot be read: " + gray.status().message();
  const DetectorOptions options = ForTarget(DetectorOptions{}, target);
  StatusOr<std::unique_ptr<TagDetector>> detector = TagDetector::Create(options);
  if (!detector.ok()) return "";
  const size_t found = (*detector)->Detect(*gray).tags.size();
  if (std::optional<LayoutHint> hint = BetterLayout(*gray, options, found)) {
    return image + " holds " + DescribeLayoutHint(*hint, options);
  }
  return image + " holds " + std::to_string(found) + " " + target.family + " tags with border_bits " +
         std::to_string(target.border_bits) + " and no more of another family or border: is the board in view, " +
         "lit and in focus? (`hexcal detect --images IMAGES --target TARGET` lists each image's tags)";
}

}  // namespace

std::string ExplainBoardPoseShortfall(const std::string& dir, const std::map<std::string, SessionImagePose>& poses,
                                      const Target& target) {
  std::map<std::string, std::vector<std::string>> by_status;
  int ok = 0;
  for (const auto& [image, pose] : poses) {
    ok += pose.ok ? 1 : 0;
    if (!pose.ok) by_status[pose.status].push_back(image);
  }
  std::string text = "only " + std::to_string(ok) + " of " + std::to_string(poses.size()) +
                     " images give a board pose, and the camera registration needs " + std::to_string(kMinBoardPoses);
  if (!by_status.empty()) text += ": " + StatusCounts(by_status);
  for (const char* status : {"no_target", "too_few_tags"}) {
    auto it = by_status.find(status);
    if (it != by_status.end()) return text + "; " + WhatTheImageHolds(dir, it->second.front(), target);
  }
  return text;
}

}  // namespace hexcal::workflow
