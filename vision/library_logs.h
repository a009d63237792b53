// Whether the log lines of the libraries under hexcal reach stderr (issue 36):
// OpenCV's own, FFmpeg's (OpenCV's videoio reads video files with it), GLib's
// (GStreamer's and Aravis' warnings) and Aravis' debug lines. hexcal says what
// failed in its own words; their lines only repeat it ("moov atom not found",
// "[ WARN:0] ... can't open camera by index") or are noise before its message.
// Off by default; `hexcal --verbose COMMAND ...` lets them through.
//
//   ShowLibraryLogs(verbose);  // once, before any image, video or camera is opened
#pragma once

namespace hexcal {

void ShowLibraryLogs(bool shown);
bool LibraryLogsShown();

// Called by ShowLibraryLogs after each change: the image and video module
// (image_codecs.cc) registers here to pass the setting to the libraries it
// has loaded (FFmpeg's, GLib's), so that this file needs none of them.
void SetLibraryLogsListener(void (*listener)());

}  // namespace hexcal
