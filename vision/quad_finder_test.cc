#include "vision/quad_finder.h"
#include "vision/quad_snap.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

namespace hexcal {
namespace {

constexpr int kSupersample = 8;

// Black squares on white, anti-aliased by area (drawn 8× larger, then averaged)
// and blurred a little, as a lens would. Corners in OpenCV pixels.
cv::Mat DrawSquares(const std::vector<std::array<Eigen::Vector2d, 4>>& squares, cv::Size size) {
  cv::Mat big(size.height * kSupersample, size.width * kSupersample, CV_8UC1, cv::Scalar(230));
  for (const auto& square : squares) {
    std::vector<cv::Point> polygon;
    for (const Eigen::Vector2d& c : square) {
      // OpenCV pixel centre x ↔ supersampled (x + 0.5) · 8 − 0.5
      polygon.emplace_back(cvRound((c.x() + 0.5) * kSupersample - 0.5), cvRound((c.y() + 0.5) * kSupersample - 0.5));
    }
    cv::fillConvexPoly(big, polygon, cv::Scalar(25));
  }
  cv::Mat small;
  cv::resize(big, small, size, 0, 0, cv::INTER_AREA);
  cv::GaussianBlur(small, small, cv::Size(), 0.7);
  return small;
}

std::array<Eigen::Vector2d, 4> Square(const Eigen::Vector2d& centre, double half, double angle) {
  std::array<Eigen::Vector2d, 4> corners;
  for (int k = 0; k < 4; ++k) {
    // Screen-counter-clockwise from the bottom-left (y down): the Quad order.
    const double a = angle + M_PI * (0.75 - 0.5 * k);
    corners[static_cast<size_t>(k)] = centre + std::sqrt(2.0) * half * Eigen::Vector2d(std::cos(a), std::sin(a));
  }
  return corners;
}

// The smallest distance from each true corner to a found one.
double WorstCornerError(const std::array<Eigen::Vector2d, 4>& truth, const std::vector<Quad>& quads) {
  double worst_square = std::numeric_limits<double>::infinity();
  for (const Quad& quad : quads) {
    double worst = 0;
    for (const Eigen::Vector2d& t : truth) {
      double best = std::numeric_limits<double>::infinity();
      for (const Eigen::Vector2d& c : quad.corners) best = std::min(best, (c - t).norm());
      worst = std::max(worst, best);
    }
    worst_square = std::min(worst_square, worst);
  }
  return worst_square;
}

TEST(QuadFinderTest, SquaresTouchingAtACornerAreFoundApart) {
  // Two tags and the small square of an aprilgrid's gap crossing between
  // them, all three meeting at single corners.
  const auto left = Square({60, 80}, 30, 0);
  const auto crossing = Square({99, 119}, 9, 0);
  const auto right = Square({138, 158}, 30, 0);
  const cv::Mat image = DrawSquares({left, crossing, right}, cv::Size(200, 200));
  std::unique_ptr<QuadFinder> finder = QuadFinder::Create(1, 0, 8).value();
  const std::vector<Quad> quads = finder->Find(image);
  EXPECT_LT(WorstCornerError(left, quads), 1.0);  // the library's scatter; the edge fit refines
  EXPECT_LT(WorstCornerError(right, quads), 1.0);
  for (const Quad& quad : quads) EXPECT_LT(SignedArea(quad.corners), 0) << "screen-counter-clockwise";
}

// The library's quad corners scatter by a few tenths of a pixel (its line fit
// runs on pixel boundaries); what the growth must not leave is a bias: without
// UndoWhiteGrowth every corner would sit 1.0-1.4 px inside the square.
TEST(QuadFinderTest, GrowthIsUndoneAtAnyAngle) {
  double radial_sum = 0;
  int corners = 0;
  for (double angle : {0.0, 0.2, 0.5, 0.785, 1.1, 1.4}) {
    const auto square = Square({100, 100}, 40, angle);
    std::unique_ptr<QuadFinder> finder = QuadFinder::Create(1, 0, 8).value();
    const std::vector<Quad> quads = finder->Find(DrawSquares({square}, cv::Size(200, 200)));
    ASSERT_EQ(quads.size(), 1u) << "angle " << angle;
    EXPECT_LT(WorstCornerError(square, quads), 1.0) << "angle " << angle;
    for (const Eigen::Vector2d& c : quads[0].corners) {
      radial_sum += (c - Eigen::Vector2d(100, 100)).norm() - std::sqrt(2.0) * 40;
      ++corners;
    }
  }
  EXPECT_LT(std::abs(radial_sum / corners), 0.25);
}

TEST(QuadFinderTest, UndoWhiteGrowthMovesEachEdgeByTheSquaresSupport) {
  const auto square = Square({0, 0}, 10, 0);
  const std::array<Eigen::Vector2d, 4> grown = UndoWhiteGrowth(square, 1);
  for (size_t k = 0; k < 4; ++k) EXPECT_NEAR((grown[k] - square[k]).norm(), std::sqrt(2.0), 1e-12);
  const auto diamond = Square({0, 0}, 10, M_PI / 4);  // edge normals at 45°: moved by √2
  const std::array<Eigen::Vector2d, 4> moved = UndoWhiteGrowth(diamond, 1);
  for (size_t k = 0; k < 4; ++k) EXPECT_NEAR(moved[k].norm() - diamond[k].norm(), 2.0, 1e-9);
}

// The edge snap (vision/quad_snap.h) against the drawn truth: from corners
// 1.5 px off, on squares down to 14 px, at several angles.
TEST(QuadSnapTest, CornersOffByPixelsLandOnTheDrawnSquare) {
  for (double half : {7.0, 12.0, 30.0}) {
    for (double angle : {0.0, 0.3, 0.7}) {
      const auto truth = Square({60, 60}, half, angle);
      const cv::Mat image = DrawSquares({truth}, cv::Size(120, 120));
      Quad start{truth};
      const Eigen::Vector2d offsets[4] = {{1.5, -1.0}, {-1.0, 1.2}, {0.8, 1.5}, {-1.5, -0.6}};
      for (size_t k = 0; k < 4; ++k) start.corners[k] += offsets[k];
      const Quad snapped = SnapQuadEdges(image, start);
      for (size_t k = 0; k < 4; ++k) {
        EXPECT_LT((snapped.corners[k] - truth[k]).norm(), 0.2) << "half " << half << ", angle " << angle << ", corner " << k;
      }
    }
  }
}

TEST(QuadSnapTest, NoEdgeLeavesTheQuadAsItWas) {
  const cv::Mat blank(120, 120, CV_8UC1, cv::Scalar(128));
  const Quad quad{Square({60, 60}, 20, 0.2)};
  const Quad snapped = SnapQuadEdges(blank, quad);
  for (size_t k = 0; k < 4; ++k) EXPECT_EQ(snapped.corners[k], quad.corners[k]);
}

}  // namespace
}  // namespace hexcal
