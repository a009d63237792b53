#include "vision/quad_snap.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>

#include "vision/bilinear.h"

namespace hexcal {
namespace {

constexpr double kSearchPx = 2.0;    // the library's range at quad_decimate 1: decimate + 1
constexpr double kSearchStepPx = 0.25;
constexpr double kHalfBaselinePx = 1.0;  // grey difference taken across 2 px
constexpr int kMinSamples = 16;
constexpr double kPxPerSample = 8.0;
constexpr int kMaxPasses = 4;
constexpr double kSettledPx = 0.02;

// A line as a point on it and its unit normal.
struct Line {
  Eigen::Vector2d point, normal;
};

// The edge from a to b moved onto the step, with `outward` pointing to the light side.
std::optional<Line> SnapEdge(const cv::Mat& gray, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                             const Eigen::Vector2d& outward) {
  const int samples = std::max(kMinSamples, static_cast<int>((b - a).norm() / kPxPerSample));
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  Eigen::Matrix2d second = Eigen::Matrix2d::Zero();
  int found = 0;
  for (int s = 0; s < samples; ++s) {
    const double alpha = (1.0 + s) / (samples + 1);
    const Eigen::Vector2d on_edge = a + alpha * (b - a);
    double weighted_offset = 0, total_weight = 0;
    for (double t = -kSearchPx; t <= kSearchPx + 1e-9; t += kSearchStepPx) {
      const Eigen::Vector2d light = on_edge + (t + kHalfBaselinePx) * outward;
      const Eigen::Vector2d dark = on_edge + (t - kHalfBaselinePx) * outward;
      const std::optional<double> g_light = BilinearGrey(gray, light.x(), light.y());
      const std::optional<double> g_dark = BilinearGrey(gray, dark.x(), dark.y());
      if (!g_light || !g_dark || *g_light <= *g_dark) continue;
      const double weight = (*g_light - *g_dark) * (*g_light - *g_dark);
      weighted_offset += weight * t;
      total_weight += weight;
    }
    if (total_weight <= 0) continue;
    const Eigen::Vector2d best = on_edge + (weighted_offset / total_weight) * outward;
    sum += best;
    second += best * best.transpose();
    ++found;
  }
  if (found < kMinSamples / 2) return std::nullopt;
  const Eigen::Vector2d mean = sum / found;
  const Eigen::Matrix2d covariance = second / found - mean * mean.transpose();
  // The normal is the direction of least spread: the smaller eigenvalue's vector.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(covariance);
  return Line{mean, eigen.eigenvectors().col(0)};
}

std::optional<Eigen::Vector2d> Meet(const Line& p, const Line& q) {
  Eigen::Matrix2d normals;
  normals << p.normal.transpose(), q.normal.transpose();
  if (std::abs(normals.determinant()) < 1e-3) return std::nullopt;
  return normals.inverse() * Eigen::Vector2d(p.normal.dot(p.point), q.normal.dot(q.point));
}

// One snap of every edge; nullopt if an edge finds no step or two edges do not meet.
std::optional<Quad> SnapOnce(const cv::Mat& gray, const Quad& quad) {
  const auto& c = quad.corners;
  const Eigen::Vector2d centre = 0.25 * (c[0] + c[1] + c[2] + c[3]);
  std::array<Line, 4> lines;  // edge k runs from corner k to k + 1
  for (size_t k = 0; k < 4; ++k) {
    const Eigen::Vector2d& a = c[k];
    const Eigen::Vector2d& b = c[(k + 1) % 4];
    Eigen::Vector2d outward = Eigen::Vector2d(-(b - a).y(), (b - a).x()).normalized();
    if (outward.dot(a - centre) < 0) outward = -outward;
    std::optional<Line> line = SnapEdge(gray, a, b, outward);
    if (!line) return std::nullopt;
    lines[k] = *line;
  }
  Quad snapped = quad;
  for (size_t k = 0; k < 4; ++k) {
    // Corner k is where edge k - 1 meets edge k.
    std::optional<Eigen::Vector2d> corner = Meet(lines[(k + 3) % 4], lines[k]);
    if (!corner) return std::nullopt;
    snapped.corners[k] = *corner;
  }
  return snapped;
}

double LargestMove(const Quad& from, const Quad& to) {
  double largest = 0;
  for (size_t k = 0; k < 4; ++k) largest = std::max(largest, (to.corners[k] - from.corners[k]).norm());
  return largest;
}

}  // namespace

Quad SnapQuadEdges(const cv::Mat& gray, const Quad& quad) {
  CV_Assert(gray.type() == CV_8UC1);
  double shortest = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < 4; ++k) shortest = std::min(shortest, (quad.corners[(k + 1) % 4] - quad.corners[k]).norm());
  // The search window is centred on the current edge; an edge off by more
  // than its half-width pulls the weighted mean back towards the start, so
  // the snap is repeated from its own result until the corners settle.
  Quad current = quad;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    std::optional<Quad> next = SnapOnce(gray, current);
    if (!next || LargestMove(quad, *next) > 0.2 * shortest) return pass == 0 ? quad : current;
    const double moved = LargestMove(current, *next);
    current = *next;
    if (moved < kSettledPx) break;
  }
  return current;
}

}  // namespace hexcal
