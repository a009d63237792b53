#include "vision/image_codecs.h"

#include <dlfcn.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "core/atomic_file.h"
#include "vision/library_logs.h"
#include "vision/opencv_io_plugin.h"

namespace hexcal {
namespace {

constexpr const char* kPluginFile = "libhexcal_opencv_io.so";

// Where the module may be: $HEXCAL_OPENCV_IO, the build's own copy (its path
// compiled in), then beside the executable and in ../lib/hexcal from it.
std::vector<std::string> PluginCandidates() {
  std::vector<std::string> paths;
  if (const char* given = std::getenv("HEXCAL_OPENCV_IO"); given && *given) paths.emplace_back(given);
  paths.emplace_back(HEXCAL_OPENCV_IO_PLUGIN);
  std::error_code error;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    paths.push_back((exe.parent_path() / kPluginFile).string());
    paths.push_back((exe.parent_path().parent_path() / "lib/hexcal" / kPluginFile).string());
  }
  return paths;
}

struct LoadedPlugin {
  const OpenCvIoPlugin* plugin = nullptr;
  std::string error;
};

LoadedPlugin LoadPlugin() {
  std::string tried;
  for (const std::string& path : PluginCandidates()) {
    // Never unloaded: OpenCV's codecs keep global state for the life of the process.
    void* handle = dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (!handle) {
      tried += (tried.empty() ? "" : "; ") + std::string(dlerror());
      continue;
    }
    using Entry = const OpenCvIoPlugin* (*)();
    auto entry = reinterpret_cast<Entry>(dlsym(handle, "hexcal_opencv_io_plugin"));
    if (!entry) return {nullptr, path + ": not a hexcal_opencv_io module"};
    const OpenCvIoPlugin* plugin = entry();
    if (plugin->version != kOpenCvIoPluginVersion) return {nullptr, path + ": from another hexcal build"};
    plugin->show_library_logs(LibraryLogsShown());
    SetLibraryLogsListener(&ApplyLibraryLogsToCodecs);  // later changes reach it too
    return {plugin, ""};
  }
  return {nullptr, "image and video support (" + std::string(kPluginFile) + ") cannot be loaded: " + tried +
                       " (rebuild hexcal, or set HEXCAL_OPENCV_IO to the module's path)"};
}

std::atomic<const OpenCvIoPlugin*> loaded_plugin{nullptr};  // for ApplyLibraryLogsToCodecs

// The plugin, loaded once by whichever thread asks first.
StatusOr<const OpenCvIoPlugin*> Plugin() {
  static const LoadedPlugin loaded = LoadPlugin();
  if (!loaded.plugin) return Status::IoError(loaded.error);
  loaded_plugin = loaded.plugin;
  return loaded.plugin;
}

}  // namespace

StatusOr<cv::Mat> DecodeImage(const std::string& bytes) {
  StatusOr<const OpenCvIoPlugin*> plugin = Plugin();
  if (!plugin.ok()) return plugin.status();
  cv::Mat image;
  if (std::string error = (*plugin)->decode(bytes, cv::IMREAD_UNCHANGED, &image); !error.empty())
    return Status::BadInput("cannot decode: " + error);
  if (image.empty()) return Status::BadInput("cannot decode: corrupt, truncated or not an image");
  return image;
}

StatusOr<cv::Mat> ReadImageFile(const std::string& path) {
  // The project's bounded read (no FIFO or device, at most kMaxImageBytes), then DecodeImage.
  StatusOr<std::string> bytes = ReadFileToString(path, kMaxImageBytes);
  if (!bytes.ok()) return bytes.status();
  StatusOr<cv::Mat> image = DecodeImage(*bytes);
  if (!image.ok() && image.status().kind() != StatusKind::kIo)
    return Status::BadInput(path + ": not an image OpenCV can read");
  return image;
}

StatusOr<std::string> EncodePng(const cv::Mat& image) {
  StatusOr<const OpenCvIoPlugin*> plugin = Plugin();
  if (!plugin.ok()) return plugin.status();
  std::string bytes;
  if (std::string error = (*plugin)->encode(".png", image, &bytes); !error.empty())
    return Status::Failed("PNG encoding failed: " + error);
  return bytes;
}

StatusOr<std::unique_ptr<VideoStream>> OpenVideoFile(const std::string& path) {
  StatusOr<const OpenCvIoPlugin*> plugin = Plugin();
  if (!plugin.ok()) return plugin.status();
  std::string error;
  std::unique_ptr<VideoStream> stream((*plugin)->open_video_file(path, &error));
  if (!stream) return Status::BadInput(path + ": not a video OpenCV can read (" + error + ")");
  return stream;
}

StatusOr<std::unique_ptr<VideoStream>> OpenVideoDevice(int index, int api) {
  StatusOr<const OpenCvIoPlugin*> plugin = Plugin();
  if (!plugin.ok()) return plugin.status();
  std::string error;
  std::unique_ptr<VideoStream> stream((*plugin)->open_video_device(index, api, &error));
  if (!stream) return Status::IoError("cannot open video device " + std::to_string(index) + " (" + error + ")");
  return stream;
}

void ApplyLibraryLogsToCodecs() {
  if (const OpenCvIoPlugin* plugin = loaded_plugin) plugin->show_library_logs(LibraryLogsShown());
}

}  // namespace hexcal
