#include "vision/edge_refine.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <locale>
#include <sstream>
#include <string>
#include <vector>

#include "core/pose.h"

namespace hexcal {
namespace {

constexpr double kMaxCornerShiftPx = 2.0;
constexpr double kCornerClearancePx = 2.5;  // band starts this far from each corner, along the edge
constexpr double kMinCellPx = 3.5;
constexpr double kMaxHalfWidthPx = 4.0;  // of the band across an edge
constexpr double kMinHalfWidthPx = 1.2;
constexpr double kMinContrast = 5;  // grey levels
constexpr double kFinalTolerancePx = 1e-4;  // the last edge fit's step; edges are good to ~1e-3 px

struct BandPixel {
  Eigen::Vector2d q;  // ideal pixel, relative to the edge's midpoint
  double t;           // along the edge, -1 .. 1 from one end to the other
  double value;
};

// Parameters of the edge model, see EdgeModel.
using EdgeParams = Eigen::Matrix<double, 8, 1>;
using EdgeMatrix = Eigen::Matrix<double, 8, 8>;
enum { kAngle, kOffset, kBlack, kContrast, kBlur, kBlackSlope, kContrastSlope, kShading };

std::string FormatPx(double value) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out.precision(2);
  out << std::fixed << value;
  return out.str();
}

// The standard normal density φ(z) and distribution Φ(z) from one exponential:
// Φ(−|z|) = ½ erfc(|z|/√2) by Abramowitz & Stegun 7.1.26 (erfc(x) ≈ t P(t) e^(−x²),
// t = 1/(1 + p x), absolute error under 1.5e-7), whose e^(−x²) is 2.5066 φ(z).
// An error of 1e-7 of the contrast is far below a grey level; erfc and exp
// were a third of the whole measurement's time (docs/vision.md).
struct NormalValues {
  double cdf, pdf;
};
NormalValues Normal(double z) {
  constexpr double kInvSqrt2Pi = 0.3989422804014327, kSqrt2Pi = 2.5066282746310002;
  const double pdf = kInvSqrt2Pi * std::exp(-0.5 * z * z);
  const double t = 1 / (1 + 0.3275911 * 0.7071067811865476 * std::abs(z));
  const double poly = t * (0.254829592 + t * (-0.284496736 + t * (1.421413741 + t * (-1.453152027 + t * 1.061405429))));
  const double lower_tail = 0.5 * poly * kSqrt2Pi * pdf;  // Φ(−|z|)
  return {z >= 0 ? 1 - lower_tail : lower_tail, pdf};
}

// Ideal coordinates of pixel (u, v), or NaN.
Eigen::Vector2d IdealAt(const IdealPixelMap* ideal, int u, int v) {
  return ideal ? ideal->At(u, v) : Eigen::Vector2d(u, v);
}

// Pixels within `half_width` of the line n · (q − midpoint) = offset and at
// least kCornerClearancePx from both ends of the edge a–b (ideal pixels);
// raw_a, raw_b bound the search in the image.
std::vector<BandPixel> CollectBand(const cv::Mat& gray, const IdealPixelMap* ideal, const Eigen::Vector2d& raw_a,
                                   const Eigen::Vector2d& raw_b, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                   const Eigen::Vector2d& midpoint, const Eigen::Vector2d& n, double offset,
                                   double half_width) {
  const Eigen::Vector2d direction(-n.y(), n.x());
  const double half_length = 0.5 * (b - a).norm();
  const double start = (a - midpoint).dot(direction), end = (b - midpoint).dot(direction);
  const double t_min = std::min(start, end) + kCornerClearancePx, t_max = std::max(start, end) - kCornerClearancePx;
  // Distortion stretches the ideal image by up to ~1.5 against the raw one here.
  const double pad = 1.5 * half_width + 3;
  const int u0 = std::max(0, static_cast<int>(std::floor(std::min(raw_a.x(), raw_b.x()) - pad)));
  const int u1 = std::min(gray.cols - 1, static_cast<int>(std::ceil(std::max(raw_a.x(), raw_b.x()) + pad)));
  const int v0 = std::max(0, static_cast<int>(std::floor(std::min(raw_a.y(), raw_b.y()) - pad)));
  const int v1 = std::min(gray.rows - 1, static_cast<int>(std::ceil(std::max(raw_a.y(), raw_b.y()) + pad)));
  std::vector<BandPixel> band;
  for (int v = v0; v <= v1; ++v) {
    const uint8_t* row = gray.ptr<uint8_t>(v);
    for (int u = u0; u <= u1; ++u) {
      const Eigen::Vector2d q = IdealAt(ideal, u, v);
      if (!q.allFinite()) continue;
      const Eigen::Vector2d rel = q - midpoint;
      const double t = rel.dot(direction);
      if (std::abs(rel.dot(n) - offset) > half_width || t < t_min || t > t_max) continue;
      band.push_back({rel, t / half_length, static_cast<double>(row[u])});
    }
  }
  return band;
}

// The image of a straight edge between black and white, blurred by a
// Gaussian of σ = s, under lighting that varies linearly across it (c) and
// along it (a1, b1):
//
//   I = G_s ⊗ [(1 + c x) (A + B H(x))] (d)
//     = A + B Φ(z) + c (d (A + B Φ(z)) + s B φ(z)),   z = d / s,
//
// with d = n(θ)·q − ρ the distance to the edge, A = a + a1 t, B = b + b1 t,
// H the unit step, and the identity G ⊗ (x f) = d (G ⊗ f) + s² (G ⊗ f)'. The
// last term matters: a brightness gradient across a blurred edge moves its
// half-way point by c s², the same way on every edge of an image; fitted
// without it, every tag shifts a little towards the light and the pose with it.
// Parameters x = (θ, ρ, a, b, s, a1, b1, c).
class EdgeModel {
 public:
  explicit EdgeModel(const EdgeParams& x)
      : x_(x), n_(std::cos(x[kAngle]), std::sin(x[kAngle])), n_dot_(-n_.y(), n_.x()) {}

  double ValueAndRow(const BandPixel& px, EdgeParams* row) const {
    const double d = n_.dot(px.q) - x_[kOffset], s = x_[kBlur], z = d / s, c = x_[kShading];
    const double a = x_[kBlack] + x_[kBlackSlope] * px.t, b = x_[kContrast] + x_[kContrastSlope] * px.t;
    const auto [cdf, pdf] = Normal(z);
    const double u = a + b * cdf;
    const double d_a = 1 + c * d;                       // dI/dA
    const double d_b = cdf + c * (d * cdf + s * pdf);   // dI/dB
    const double d_d = b * pdf / s + c * u;             // dI/dd
    const double d_s = -b * z * pdf / s + c * b * pdf;  // dI/ds
    *row << d_d * n_dot_.dot(px.q), -d_d, d_a, d_b, d_s, d_a * px.t, d_b * px.t, d * u + s * b * pdf;
    return u + c * (d * u + s * b * pdf);
  }

 private:
  EdgeParams x_;
  Eigen::Vector2d n_, n_dot_;
};

// The band's sum of squared residuals at x, with JᵀJ and Jᵀr for every
// parameter but the shading c (its row and column made trivial: it is held fixed).
struct Linearisation {
  double cost = 0;
  EdgeMatrix jtj = EdgeMatrix::Zero();
  EdgeParams jtr = EdgeParams::Zero();
};

Linearisation Linearise(const std::vector<BandPixel>& band, const EdgeParams& x) {
  const EdgeModel model(x);
  Linearisation at;
  EdgeParams row;
  for (const BandPixel& px : band) {
    const double r = model.ValueAndRow(px, &row) - px.value;
    row[kShading] = 0;
    at.cost += r * r;
    at.jtj.noalias() += row * row.transpose();
    at.jtr += row * r;
  }
  at.jtj(kShading, kShading) = 1;
  return at;
}

// Levenberg–Marquardt from x over every parameter but the shading c, which
// the tag as a whole determines (RefineTagCorners), until a step moves the
// edge by under `tolerance_px` (and 1e-6 rad). Each trial point is linearised
// once: when it is accepted, that linearisation serves the next step.
// Returns why the fit is not used, or "" when it is.
std::string FitEdge(const std::vector<BandPixel>& band, double half_width, double tolerance_px, EdgeParams& x,
                    EdgeFit* fit) {
  if (band.size() < 16) return "only " + std::to_string(band.size()) + " pixels in its band";
  const double initial_angle = x[kAngle];
  double lambda = 1e-3;
  Linearisation at = Linearise(band, x);
  for (int iteration = 0; iteration < 40; ++iteration) {
    bool improved = false;
    EdgeParams step = EdgeParams::Zero();
    while (lambda < 1e8) {
      EdgeMatrix damped = at.jtj;
      damped.diagonal() *= 1 + lambda;
      step = -damped.ldlt().solve(at.jtr);
      EdgeParams next = x + step;
      next[kBlur] = std::max(next[kBlur], 0.05);
      Linearisation trial = Linearise(band, next);
      if (trial.cost < at.cost) {
        x = next;
        at = trial;
        lambda = std::max(1e-7, lambda * 0.2);
        improved = true;
        break;
      }
      lambda *= 10;
    }
    if (!improved || (std::abs(step[kOffset]) < tolerance_px && std::abs(step[kAngle]) < 1e-6)) break;
  }
  // Covariance at the minimum: σ² (JᵀJ)⁻¹, the marginal block of (θ, ρ).
  const double cost = at.cost;
  const double variance = cost / static_cast<double>(band.size() - (x.size() - 1));
  const EdgeMatrix covariance = variance * at.jtj.inverse();

  fit->angle = x[kAngle];
  fit->offset = x[kOffset];
  fit->covariance = covariance.topLeftCorner<2, 2>();
  fit->black = x[kBlack];
  fit->contrast = x[kContrast];
  fit->blur = x[kBlur];
  fit->rms = std::sqrt(cost / band.size());
  fit->pixels = static_cast<int>(band.size());
  if (!(x[kContrast] > kMinContrast)) return "contrast " + FormatPx(x[kContrast]) + " grey levels";
  if (!(x[kBlur] > 0.1)) return "no blur left to fit (" + FormatPx(x[kBlur]) + " px)";
  if (!(x[kBlur] < half_width)) {
    return "blur " + FormatPx(x[kBlur]) + " px wider than its band (" + FormatPx(half_width) + " px)";
  }
  if (!(std::cos(x[kAngle] - initial_angle) > std::cos(DegToRad(10)))) return "turned more than 10 degrees";
  if (!fit->covariance.allFinite()) return "no covariance";
  return "";
}

// One edge's fit and the pixels it used.
struct EdgeState {
  EdgeParams x = EdgeParams::Zero();
  std::vector<BandPixel> band;
  double half_width = 0;
  EdgeFit fit;
};

// Fits one edge: a first fit in a band around the approximate line, then a
// second in a band centred on the first fit's line, so that the band is
// symmetric about the edge whatever the approximate corners' error, and
// narrowed to keep the blurred edges of the neighbouring cells (one `cell`
// away) out: the transition of a blurred step spans about ±3 s.
// Returns why the edge cannot be fitted, or "" when it is.
std::string FitEdgeTwice(const cv::Mat& gray, const IdealPixelMap* ideal, const Eigen::Vector2d& raw_a,
                  const Eigen::Vector2d& raw_b, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                  const Eigen::Vector2d& n0, double border, EdgeState* edge) {
  EdgeParams& x = edge->x;
  edge->fit.midpoint = 0.5 * (a + b);
  x[kAngle] = std::atan2(n0.y(), n0.x());
  x[kBlur] = 0.8;
  edge->half_width = std::min(kMaxHalfWidthPx, border - 2.0);
  for (int pass = 0; pass < 2; ++pass) {
    // The second band follows the blur the first fit measured: wide enough to
    // hold the step (±2 s), clear of the next edge's step (3 s from it).
    if (pass == 1) edge->half_width = std::min(std::max(kMaxHalfWidthPx, 2 * x[kBlur]), border - 3 * x[kBlur]);
    if (edge->half_width < kMinHalfWidthPx) {
      return "blur " + FormatPx(x[kBlur]) + " px too wide for a " + FormatPx(border) + " px border";
    }
    const Eigen::Vector2d n(std::cos(x[kAngle]), std::sin(x[kAngle]));
    edge->band = CollectBand(gray, ideal, raw_a, raw_b, a, b, edge->fit.midpoint, n, x[kOffset], edge->half_width);
    if (pass == 0) {  // start from the mean grey on either side
      double dark = 0, bright = 0;
      int dark_count = 0, bright_count = 0;
      for (const BandPixel& p : edge->band) {
        const double d = p.q.dot(n);
        if (d < -0.5 * edge->half_width) dark += p.value, ++dark_count;
        if (d > 0.5 * edge->half_width) bright += p.value, ++bright_count;
      }
      if (dark_count == 0 || bright_count == 0) return "no dark or no bright side";
      x[kBlack] = dark / dark_count;
      x[kContrast] = bright / bright_count - x[kBlack];
    }
    // Both passes only place the band and start the last fit (RefineTagCorners):
    // to a hundredth of a pixel, the first to a twentieth.
    const double tolerance_px = pass == 0 ? 0.05 : 0.01;
    if (std::string why = FitEdge(edge->band, edge->half_width, tolerance_px, x, &edge->fit); !why.empty()) return why;
    if (std::abs(x[kOffset]) > edge->half_width) {
      return "moved " + FormatPx(std::abs(x[kOffset])) + " px, out of its band";
    }
  }
  return "";
}

// The relative brightness gradient over the tag (per ideal pixel), from the
// contrast of its four edges: ln b_k = β + g · (m_k − centre) by least squares.
Eigen::Vector2d LightingGradient(const std::array<EdgeState, 4>& edges, const Eigen::Vector2d& centre) {
  Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
  Eigen::Vector3d aty = Eigen::Vector3d::Zero();
  for (const EdgeState& edge : edges) {
    const Eigen::Vector3d row(1, edge.fit.midpoint.x() - centre.x(), edge.fit.midpoint.y() - centre.y());
    ata += row * row.transpose();
    aty += row * std::log(edge.x[kContrast]);
  }
  const Eigen::Vector3d solution = ata.ldlt().solve(aty);
  return solution.allFinite() ? Eigen::Vector2d(solution[1], solution[2]) : Eigen::Vector2d::Zero();
}

// Corner k where edge k-1 (into it) meets edge k (out of it), in the distorted
// image; `lines` holds (angle, offset) of the four edges.
std::optional<std::array<Eigen::Vector2d, 4>> Intersections(const std::array<EdgeFit, 4>& edges,
                                                            const Eigen::Matrix<double, 8, 1>& lines,
                                                            const IdealPixelMap* ideal) {
  std::array<Eigen::Vector2d, 4> corners;
  for (int k = 0; k < 4; ++k) {
    const int in = (k + 3) % 4, out = k;
    Eigen::Matrix2d normals;
    Eigen::Vector2d offsets;
    for (int row = 0; row < 2; ++row) {
      const int e = row == 0 ? in : out;
      const Eigen::Vector2d n(std::cos(lines[2 * e]), std::sin(lines[2 * e]));
      normals.row(row) = n.transpose();
      offsets[row] = lines[2 * e + 1] + n.dot(edges[static_cast<size_t>(e)].midpoint);
    }
    if (std::abs(normals.determinant()) < std::sin(DegToRad(10))) return std::nullopt;
    const Eigen::Vector2d q = normals.inverse() * offsets;
    corners[static_cast<size_t>(k)] = ideal ? ideal->camera().DistortedPixel(q) : q;
  }
  return corners;
}

// Covariance of the corners: J diag(Σ_edge) Jᵀ, J = d corners / d lines by
// central differences.
std::optional<Eigen::Matrix<double, 8, 8>> CornerCovariance(const std::array<EdgeFit, 4>& edges,
                                                            const Eigen::Matrix<double, 8, 1>& lines,
                                                            const IdealPixelMap* ideal) {
  Eigen::Matrix<double, 8, 8> jacobian, line_covariance = Eigen::Matrix<double, 8, 8>::Zero();
  for (int p = 0; p < 8; ++p) {
    const double h = p % 2 == 0 ? 1e-6 : 1e-4;  // radians, pixels
    Eigen::Matrix<double, 8, 1> plus = lines, minus = lines;
    plus[p] += h;
    minus[p] -= h;
    const std::optional<std::array<Eigen::Vector2d, 4>> a = Intersections(edges, plus, ideal);
    const std::optional<std::array<Eigen::Vector2d, 4>> b = Intersections(edges, minus, ideal);
    if (!a || !b) return std::nullopt;
    for (int k = 0; k < 4; ++k)
      jacobian.block<2, 1>(2 * k, p) = ((*a)[static_cast<size_t>(k)] - (*b)[static_cast<size_t>(k)]) / (2 * h);
  }
  for (int k = 0; k < 4; ++k) line_covariance.block<2, 2>(2 * k, 2 * k) = edges[static_cast<size_t>(k)].covariance;
  return jacobian * line_covariance * jacobian.transpose();
}

}  // namespace

std::optional<RefinedTag> RefineTagCorners(const cv::Mat& gray, const IdealPixelMap* ideal, int width_at_border,
                                           int border_bits, const std::array<Eigen::Vector2d, 4>& corners,
                                           std::string* failure) {
  CV_Assert(gray.type() == CV_8UC1);
  auto fail = [&](const std::string& why) -> std::optional<RefinedTag> {
    if (failure) *failure = why;
    return std::nullopt;
  };
  std::array<Eigen::Vector2d, 4> ideal_corners;
  for (size_t k = 0; k < 4; ++k) {
    if (!ideal) {
      ideal_corners[k] = corners[k];
      continue;
    }
    const std::optional<Eigen::Vector2d> q = ideal->camera().IdealPixel(corners[k]);
    if (!q) return fail("corner " + std::to_string(k) + " is outside the camera model");
    ideal_corners[k] = *q;
  }
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double perimeter = 0;
  for (size_t k = 0; k < 4; ++k) {
    centre += 0.25 * ideal_corners[k];
    perimeter += (ideal_corners[(k + 1) % 4] - ideal_corners[k]).norm();
  }
  // Inside, the black border is border_bits cells deep and a white data bit
  // may follow it; outside, the white gap is at least as wide (Target::Validate).
  const double border = border_bits * perimeter / 4 / width_at_border;
  if (border < kMinCellPx) {
    return fail("black border of " + FormatPx(border) + " px (under " + FormatPx(kMinCellPx) + ")");
  }

  std::array<EdgeState, 4> edges;
  for (size_t k = 0; k < 4; ++k) {
    const size_t next = (k + 1) % 4;
    const Eigen::Vector2d along = ideal_corners[next] - ideal_corners[k];
    Eigen::Vector2d n(-along.y(), along.x());
    n.normalize();
    if (n.dot(0.5 * (ideal_corners[k] + ideal_corners[next]) - centre) < 0) n = -n;  // outward
    const std::string why =
        FitEdgeTwice(gray, ideal, corners[k], corners[next], ideal_corners[k], ideal_corners[next], n, border, &edges[k]);
    if (!why.empty()) return fail("edge " + std::to_string(k) + ": " + why);
  }
  // The lighting across each edge, from the tag's four contrasts, and a last
  // fit of each edge with it (EdgeModel: it moves an edge by c s²).
  const Eigen::Vector2d gradient = LightingGradient(edges, centre);
  RefinedTag tag;
  Eigen::Matrix<double, 8, 1> lines;
  for (size_t k = 0; k < 4; ++k) {
    EdgeState& edge = edges[k];
    edge.x[kShading] = gradient.dot(Eigen::Vector2d(std::cos(edge.x[kAngle]), std::sin(edge.x[kAngle])));
    if (std::string why = FitEdge(edge.band, edge.half_width, kFinalTolerancePx, edge.x, &edge.fit); !why.empty()) {
      return fail("edge " + std::to_string(k) + " with lighting: " + why);
    }
    tag.edges[k] = edge.fit;
    lines.segment<2>(static_cast<Eigen::Index>(2 * k)) << edge.fit.angle, edge.fit.offset;
  }
  const std::optional<std::array<Eigen::Vector2d, 4>> refined = Intersections(tag.edges, lines, ideal);
  if (!refined) return fail("edges meet at under 10 degrees");
  for (size_t k = 0; k < 4; ++k) {
    const double shift = ((*refined)[k] - corners[k]).norm();
    if (shift > kMaxCornerShiftPx) {
      return fail("corner " + std::to_string(k) + " would move " + FormatPx(shift) + " px (over " +
                  FormatPx(kMaxCornerShiftPx) + ")");
    }
  }
  tag.corners = *refined;
  const std::optional<Eigen::Matrix<double, 8, 8>> covariance = CornerCovariance(tag.edges, lines, ideal);
  if (!covariance) return fail("edges meet at under 10 degrees");
  tag.covariance = *covariance;
  return tag;
}

}  // namespace hexcal
