// Session work shared by panels, run on worker threads (no widgets here).
#pragma once

#include <string>
#include <vector>

#include "core/session.h"
#include "ui/background_job.h"
#include "vision/camera.h"
#include "vision/target.h"

namespace hexcal::ui {

// Measures `files` and writes measurements.csv with one row per file, named by
// file name as `calibrate --session` does. Cancelled: the file is unchanged.
// `usable` counts the images with an ok target pose.
Status MeasureImagesInto(const std::vector<std::string>& files, const Camera& camera, const Target& target,
                         const std::string& measurements_csv, const JobContext& context, int* usable);

}  // namespace hexcal::ui
