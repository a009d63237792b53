// Moves a quad's edges onto the image's dark-to-light transitions, as the
// AprilTag library does after its quad fit (its `refine_edges`): along each
// edge, at evenly spaced points, the position of the strongest step from the
// dark inside to the light outside is found within ±2 px along the normal
// (each offset weighted by the squared grey difference across 2 px), a line
// is fitted to those positions (total least squares), and neighbouring lines
// meet in the new corners. Unlike the library, the snap is repeated from its
// own result until the corners move less than 0.02 px (at most 4 times): a
// search window not centred on the edge biases the weighted mean towards the
// start (0.3 px from 1.5 px off in one pass, under 0.2 px when repeated;
// quad_finder_test).
//
// The segmentation's quad runs along thresholded pixel boundaries; on tags of
// 14 px it is 1–2 px off, the library's snapped quad 0.65 px at most. hexcal's
// decoder samples cells through the quad, and the sub-pixel edge fit
// (vision/edge_refine.h) starts from it.
//
//   Quad snapped = SnapQuadEdges(gray, quad);  // quad unchanged if an edge finds no step
#pragma once

#include <opencv2/core.hpp>

#include "vision/quad_finder.h"

namespace hexcal {

// `gray`: CV_8UC1; corners in OpenCV's pixel convention. A corner that would
// move by more than a fifth of the shorter side, or any edge without a step,
// leaves the quad as it was.
Quad SnapQuadEdges(const cv::Mat& gray, const Quad& quad);

}  // namespace hexcal
