#include "vision/tag_decoder.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>

#include "vision/bilinear.h"
#include "vision/tag_family.h"

namespace hexcal {
namespace {

constexpr double kSharpening = 0.25;  // the AprilTag library's decode_sharpening
constexpr int kMinWhiteSamples = 8;   // of the white ring, inside the image

// Tag-cell coordinates (x right, y down, cells; the black square's top-left
// corner at 0) to pixels, through the four corners in AprilTag order.
Eigen::Matrix3d CellsToPixels(const std::array<Eigen::Vector2d, 4>& corners, double width) {
  const std::array<Eigen::Vector2d, 4> cells = {
      Eigen::Vector2d(0, width), Eigen::Vector2d(width, width), Eigen::Vector2d(width, 0), Eigen::Vector2d(0, 0)};
  Eigen::Matrix<double, 8, 8> a = Eigen::Matrix<double, 8, 8>::Zero();
  Eigen::Matrix<double, 8, 1> b;
  for (int k = 0; k < 4; ++k) {
    const double x = cells[static_cast<size_t>(k)].x(), y = cells[static_cast<size_t>(k)].y();
    const double u = corners[static_cast<size_t>(k)].x(), v = corners[static_cast<size_t>(k)].y();
    a.row(2 * k) << x, y, 1, 0, 0, 0, -u * x, -u * y;
    a.row(2 * k + 1) << 0, 0, 0, x, y, 1, -v * x, -v * y;
    b(2 * k) = u;
    b(2 * k + 1) = v;
  }
  const Eigen::Matrix<double, 8, 1> h = a.fullPivLu().solve(b);
  Eigen::Matrix3d homography;
  homography << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), 1;
  return homography;
}

// Bilinear grey value at (x, y), OpenCV convention; NaN outside the image.
double Sample(const cv::Mat& gray, const Eigen::Matrix3d& cells_to_pixels, double x, double y) {
  const Eigen::Vector3d p = cells_to_pixels * Eigen::Vector3d(x, y, 1);
  return BilinearGrey(gray, p.x() / p.z(), p.y() / p.z()).value_or(std::numeric_limits<double>::quiet_NaN());
}

// A plane a + b x + c y through grey samples, least squares.
class GreyModel {
 public:
  void Add(double x, double y, double grey) {
    if (std::isnan(grey)) return;
    const Eigen::Vector3d row(1, x, y);
    normal_ += row * row.transpose();
    rhs_ += row * grey;
    ++count_;
  }
  int count() const { return count_; }
  std::optional<Eigen::Vector3d> Fit() const {
    Eigen::LDLT<Eigen::Matrix3d> solver(normal_);
    if (solver.info() != Eigen::Success || !(solver.rcond() > 1e-12)) return std::nullopt;
    return solver.solve(rhs_);
  }

 private:
  Eigen::Matrix3d normal_ = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs_ = Eigen::Vector3d::Zero();
  int count_ = 0;
};

// The bits read with the quad's corners taken one step further round
// (corner k + 1 as corner k): data cell (i, j) of the new reading is cell
// (d − 1 − j, i) of the old, d the data width.
uint64_t QuarterTurn(uint64_t bits, int d) {
  uint64_t turned = 0;
  for (int row = 0; row < d; ++row) {
    for (int col = 0; col < d; ++col) {
      if (bits >> ((d - 1 - col) * d + row) & 1) turned |= uint64_t{1} << (row * d + col);
    }
  }
  return turned;
}

double PlaneAt(const Eigen::Vector3d& plane, double x, double y) { return plane(0) + plane(1) * x + plane(2) * y; }

// The black model from the border cells and the white one from the ring of
// cells just outside the black square, its four corner cells left out.
std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> FitGreyModels(const cv::Mat& gray,
                                                                         const Eigen::Matrix3d& cells_to_pixels,
                                                                         int width, int border) {
  GreyModel black, white;
  for (int row = -1; row <= width; ++row) {
    for (int col = -1; col <= width; ++col) {
      const bool outside = row < 0 || col < 0 || row >= width || col >= width;
      const bool ring_corner = (row < 0 || row >= width) && (col < 0 || col >= width);
      const int ring = std::min(std::min(row, col), std::min(width - 1 - row, width - 1 - col));
      const double x = col + 0.5, y = row + 0.5;
      if (outside && !ring_corner) white.Add(x, y, Sample(gray, cells_to_pixels, x, y));
      if (!outside && ring < border) black.Add(x, y, Sample(gray, cells_to_pixels, x, y));
    }
  }
  if (white.count() < kMinWhiteSamples) return std::nullopt;
  const std::optional<Eigen::Vector3d> b = black.Fit(), w = white.Fit();
  if (!b || !w) return std::nullopt;
  return std::make_pair(*b, *w);
}

}  // namespace

StatusOr<TagCodebook> TagCodebook::Create(const std::string& family, int border_bits) {
  const std::optional<TagFamilyInfo> info = FindTagFamily(family);
  if (!info) return Status::BadInput("tag family '" + family + "' is not supported");
  if (border_bits != 1 && border_bits != 2) return Status::BadInput("border_bits: must be 1 or 2");
  TagCodebook codebook;
  codebook.border_bits_ = border_bits;
  codebook.data_width_ = info->width_at_border - 2;  // the library's families have a one-cell border
  const int offset = (info->total_width - codebook.data_width_) / 2;
  for (const TagCells& tag : TagCellsOf(family, 0, info->num_codes)) {
    uint64_t bits = 0;
    for (int row = 0; row < codebook.data_width_; ++row) {
      for (int col = 0; col < codebook.data_width_; ++col) {
        if (tag.IsBlack(offset + row, offset + col)) bits |= uint64_t{1} << (row * codebook.data_width_ + col);
      }
    }
    codebook.codes_.push_back(bits);
  }
  return codebook;
}

std::optional<TagCodebook::Reading> TagCodebook::Read(const cv::Mat& gray,
                                                      const std::array<Eigen::Vector2d, 4>& corners) const {
  const int width = width_at_border(), d = data_width_;
  const Eigen::Matrix3d cells_to_pixels = CellsToPixels(corners, width);
  const auto models = FitGreyModels(gray, cells_to_pixels, width, border_bits_);
  if (!models) return std::nullopt;
  // value − threshold at every data cell, with a ring of zeros for the sharpening.
  std::vector<double> diff(static_cast<size_t>((d + 2) * (d + 2)), 0.0);
  auto at = [&](int row, int col) -> double& { return diff[static_cast<size_t>((row + 1) * (d + 2) + col + 1)]; };
  for (int row = 0; row < d; ++row) {
    for (int col = 0; col < d; ++col) {
      const double x = border_bits_ + col + 0.5, y = border_bits_ + row + 0.5;
      const double grey = Sample(gray, cells_to_pixels, x, y);
      if (std::isnan(grey)) return std::nullopt;
      at(row, col) = grey - 0.5 * (PlaneAt(models->first, x, y) + PlaneAt(models->second, x, y));
    }
  }
  Reading reading;
  double white_sum = 0, black_sum = 0, white_count = 1, black_count = 1;  // the library starts its counts at 1
  for (int row = 0; row < d; ++row) {
    for (int col = 0; col < d; ++col) {
      const double laplacian = 4 * at(row, col) - at(row - 1, col) - at(row + 1, col) - at(row, col - 1) - at(row, col + 1);
      const double value = at(row, col) + kSharpening * laplacian;
      if (value > 0) {
        white_sum += value;
        ++white_count;
      } else {
        black_sum -= value;
        ++black_count;
        reading.bits |= uint64_t{1} << (row * d + col);
      }
    }
  }
  reading.decision_margin = std::min(white_sum / white_count, black_sum / black_count);
  return reading;
}

std::optional<DecodedTag> TagCodebook::Decode(const cv::Mat& gray, const Quad& quad, int max_hamming) const {
  CV_Assert(gray.type() == CV_8UC1);
  // The cells are read once, in the quad's own order; each rotation of the
  // corners reads the same physical cells (the same homography up to a turn
  // of the square), so its bits are a turn of these and its margin the same.
  const std::optional<Reading> reading = Read(gray, quad.corners);
  if (!reading) return std::nullopt;
  std::optional<DecodedTag> best;
  uint64_t bits = reading->bits;
  for (int rotation = 0; rotation < 4; ++rotation, bits = QuarterTurn(bits, data_width_)) {
    for (size_t id = 0; id < codes_.size(); ++id) {
      const int hamming = __builtin_popcountll(bits ^ codes_[id]);
      if (hamming > max_hamming || (best && hamming >= best->hamming)) continue;
      std::array<Eigen::Vector2d, 4> corners;
      for (size_t k = 0; k < 4; ++k) corners[k] = quad.corners[(k + static_cast<size_t>(rotation)) % 4];
      best = DecodedTag{static_cast<int>(id), hamming, reading->decision_margin, corners};
    }
  }
  return best;
}

}  // namespace hexcal
