#include "flip.hpp"
#include "../base/parallel_for.hpp"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>

// Section names below are those of the FLIP paper (Andersson et al. 2020): "colour pipeline" (its
// spatial filtering, colour space and colour metric) and "feature pipeline" (edge and point detection).
namespace dqskin {
namespace {

constexpr double kPi = std::numbers::pi;

// Colour metric: HyAB raised to q_c, then mapped piecewise-linearly so that the first p_c of the largest
// difference (green against blue) covers [0, p_t].
constexpr double kQc = 0.7, kPc = 0.4, kPt = 0.95;
// Feature pipeline: the edge detector's width in degrees (two standard deviations) and the exponent.
constexpr double kEdgeWidthDegrees = 0.082;  // q_f = 1/2: a square root where ΔE_f is made

// Contrast sensitivity of one opponent channel as a sum of two Gaussians in frequency, a1 e^(−b1 ω²) +
// a2 e^(−b2 ω²) (ω in cycles per degree, b in degrees²); the achromatic and red–green ones have one.
struct Csf {
  double a1, b1, a2, b2;
};
constexpr Csf kAchromatic{1, 0.0047, 0, 1e-5}, kRedGreen{1, 0.0053, 0, 1e-5}, kBlueYellow{34.1, 0.04, 13.5, 0.025};
constexpr double kWidestB = 0.04;  // the largest b above: it sets every channel's filter radius

// Linear sRGB (D65) to CIE XYZ, the rational form of the standard matrix; its rows sum to the white.
glm::dmat3 rgb_to_xyz() {
  const double m[3][3] = {{10135552.0 / 24577794, 8788810.0 / 24577794, 4435075.0 / 24577794},
                          {2613072.0 / 12288897, 8788810.0 / 12288897, 887015.0 / 12288897},
                          {1425312.0 / 73733382, 8788810.0 / 73733382, 70074185.0 / 73733382}};
  glm::dmat3 out;
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) out[col][row] = m[row][col];  // GLM is column-major
  return out;
}

struct Colour {
  glm::dmat3 to_xyz = rgb_to_xyz();
  glm::dmat3 to_rgb = glm::inverse(to_xyz);
  glm::dvec3 white = to_xyz * glm::dvec3(1.0);  // (0.9504, 1, 1.0889)

  // YyCxCz: CIELAB without its cube root, linear in XYZ, so that filtering it is filtering light.
  glm::dvec3 ycxcz(const glm::dvec3& rgb) const {
    const glm::dvec3 n = to_xyz * rgb / white;
    return {116 * n.y - 16, 500 * (n.x - n.y), 200 * (n.y - n.z)};
  }
  glm::dvec3 rgb_of_ycxcz(const glm::dvec3& o) const {
    const double y = (o.x + 16) / 116;
    return to_rgb * (glm::dvec3(y + o.y / 500, y, y - o.z / 200) * white);
  }
  // CIELAB of linear RGB with chroma scaled by lightness (the Hunt effect): L*, 0.01 L* a*, 0.01 L* b*.
  glm::dvec3 hunt_lab(const glm::dvec3& rgb) const {
    const glm::dvec3 t = to_xyz * rgb / white;
    const auto f = [](double v) {
      constexpr double d = 6.0 / 29.0;
      return v > d * d * d ? std::cbrt(v) : v / (3 * d * d) + 4.0 / 29.0;
    };
    const double l = 116 * f(t.y) - 16;
    return {l, 0.01 * l * 500 * (f(t.x) - f(t.y)), 0.01 * l * 200 * (f(t.y) - f(t.z))};
  }
};

// Lengths here are of colour and gradient differences, far from overflow: sqrt of the sum of squares,
// without std::hypot's scaling.
double length(double x, double y) { return std::sqrt(x * x + y * y); }

double hyab(const glm::dvec3& a, const glm::dvec3& b) { return std::abs(a.x - b.x) + length(a.y - b.y, a.z - b.z); }

double srgb_decode(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// 8-bit images (most renders) hold only 256 values, k / 255 as a float: those are looked up, the same
// numbers without a pow per channel; any other value is computed.
struct SrgbTable {
  float key[256];
  double linear[256];
  SrgbTable() {
    for (int k = 0; k < 256; ++k) {
      key[k] = float(k) / 255.0f;
      linear[k] = srgb_decode(double(key[k]));
    }
  }
};

double srgb_to_linear(float encoded) {
  static const SrgbTable table;
  const double c = std::clamp(double(encoded), 0.0, 1.0);
  const auto k = size_t(std::lround(c * 255));
  return table.key[k] == encoded ? table.linear[k] : srgb_decode(c);
}

// The rows [begin, end) of a band whose filtered values are wanted: passes along y compute only those.
struct Rows {
  size_t begin, end;
};

// Planes freed while a band is computed, kept for the next ones of the same band on this thread: a band
// makes some forty planes of one size, and taking fresh pages from the system for each cost as much as a
// third of FLIP's time in page faults. Emptied when the band is done (release_spare_planes).
thread_local std::vector<std::vector<double>> spare_planes;

void release_spare_planes() { spare_planes.clear(); }

// An image plane, row by row, zeroed.
struct Plane {
  size_t width = 0, height = 0;
  std::vector<double> v;
  Plane(size_t w, size_t h) : width(w), height(h) {
    if (!spare_planes.empty()) {
      v = std::move(spare_planes.back());
      spare_planes.pop_back();
    }
    v.assign(w * h, 0.0);
  }
  Plane(const Plane&) = default;
  Plane(Plane&&) = default;
  Plane& operator=(const Plane&) = default;
  Plane& operator=(Plane&&) = default;
  ~Plane() {
    if (v.capacity() == 0) return;
    try {
      spare_planes.push_back(std::move(v));
    } catch (...) {  // no room to keep it: it is freed instead (a destructor must not throw)
    }
  }
};

// Correlates along rows (horizontal) or columns with an odd kernel centred on its middle, the border
// pixels repeated beyond the edge. Rows go through a padded copy and columns are summed a whole row at a
// time, so that the inner loops run over contiguous memory without a clamp per tap.
// Built for AVX2 too and chosen at run time (four doubles a vector instead of SSE2's two); without FMA,
// which the "avx2" target does not enable, so that each product and sum rounds as on any x86-64 and the
// figures are the same bit for bit on every machine.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
Plane correlate(const Plane& in, const std::vector<double>& kernel, bool horizontal, Rows rows) {
  Plane out(in.width, in.height);
  const size_t r = kernel.size() / 2, w = in.width, h = in.height;
  if (horizontal) {
    std::vector<double> padded(w + 2 * r);
    for (size_t y = 0; y < h; ++y) {
      const double* row = &in.v[y * w];
      for (size_t i = 0; i < padded.size(); ++i) padded[i] = row[std::clamp(i, r, r + w - 1) - r];
      // Tap by tap over the whole row (each output still sums its taps in kernel order, from 0): the
      // inner loop is a vector multiply-add over contiguous memory, not a reduction the compiler may not
      // reorder.
      double* dst = &out.v[y * w];
      for (size_t k = 0; k < kernel.size(); ++k) {
        const double weight = kernel[k];
        const double* src = padded.data() + k;
        for (size_t x = 0; x < w; ++x) dst[x] += weight * src[x];
      }
    }
  } else {
    for (size_t y = rows.begin; y < rows.end; ++y) {
      double* dst = &out.v[y * w];
      for (size_t k = 0; k < kernel.size(); ++k) {
        const size_t sy = size_t(std::clamp(long(y + k) - long(r), 0L, long(h) - 1));
        const double* src = &in.v[sy * w];
        for (size_t x = 0; x < w; ++x) dst[x] += kernel[k] * src[x];
      }
    }
  }
  return out;
}

Plane separable(const Plane& in, const std::vector<double>& along_x, const std::vector<double>& along_y, Rows rows) {
  return correlate(correlate(in, along_x, true, rows), along_y, false, rows);
}

// Colour pipeline, spatial filtering: the CSF's spatial kernel, a1 √(π/b1) e^(−π² r²/b1) + a2 √(π/b2)
// e^(−π² r²/b2) with r in degrees, sampled at the pixels within three standard deviations of the widest
// Gaussian of all channels and normalized to sum 1. Each Gaussian term is separable, so the 2-D kernel is
// applied as one pass along x and one along y per term.
Plane csf_filter(const Plane& channel, const Csf& csf, double ppd, Rows rows) {
  const long radius = long(std::ceil(3 * std::sqrt(kWidestB / (2 * kPi * kPi)) * ppd));
  struct Term {
    double weight;
    std::vector<double> g;
  };
  std::vector<Term> terms;
  double total = 0;  // the 2-D kernel's sum
  for (const auto& [a, b] : {std::pair{csf.a1, csf.b1}, std::pair{csf.a2, csf.b2}}) {
    if (a == 0) continue;
    Term t{a * std::sqrt(kPi / b), {}};
    double sum = 0;
    for (long i = -radius; i <= radius; ++i) {
      const double r = double(i) / ppd;
      t.g.push_back(std::exp(-kPi * kPi * r * r / b));
      sum += t.g.back();
    }
    total += t.weight * sum * sum;
    terms.push_back(std::move(t));
  }
  Plane out(channel.width, channel.height);
  for (const Term& t : terms) {
    const Plane pass = separable(channel, t.g, t.g, rows);
    for (size_t i = rows.begin * out.width; i < rows.end * out.width; ++i) out.v[i] += t.weight / total * pass.v[i];
  }
  return out;
}

// Feature pipeline: a Gaussian of standard deviation half the edge width (in pixels) and its first and
// second derivatives, each derivative scaled so that its positive weights sum to 1 and its negative ones to
// −1 (a flat region gives 0, a step of 1 gives about 1 whatever the viewing distance).
struct FeatureKernels {
  std::vector<double> gaussian, edge, point;
};

FeatureKernels feature_kernels(double ppd) {
  const double sigma = 0.5 * kEdgeWidthDegrees * ppd;
  const long radius = long(std::ceil(3 * sigma));
  FeatureKernels k;
  double sum = 0;
  for (long i = -radius; i <= radius; ++i) {
    const double x = double(i), g = std::exp(-x * x / (2 * sigma * sigma));
    k.gaussian.push_back(g);
    k.edge.push_back(-x * g);
    k.point.push_back((x * x / (sigma * sigma) - 1) * g);
    sum += g;
  }
  for (double& g : k.gaussian) g /= sum;
  for (std::vector<double>* d : {&k.edge, &k.point}) {
    double positive = 0, negative = 0;
    for (double v : *d) (v > 0 ? positive : negative) += v;
    for (double& v : *d) v = v > 0 ? v / positive : v < 0 ? v / -negative : 0;
  }
  return k;
}

// The edge and point strength of each pixel: the length of the (x, y) response of each detector.
struct Features {
  Plane edges, points;
};

Features features(const Plane& luminance, const FeatureKernels& k, Rows rows) {
  const Plane smoothed_along_x = correlate(luminance, k.gaussian, true, rows);  // shared by both detectors' y response
  const auto magnitude = [&](const std::vector<double>& d) {
    const Plane dx = correlate(correlate(luminance, d, true, rows), k.gaussian, false, rows);
    const Plane dy = correlate(smoothed_along_x, d, false, rows);
    Plane m(luminance.width, luminance.height);
    for (size_t i = rows.begin * m.width; i < rows.end * m.width; ++i) m.v[i] = length(dx.v[i], dy.v[i]);
    return m;
  };
  return {magnitude(k.edge), magnitude(k.point)};
}

// One image in opponent space (three planes) and its luminance Y / Y_white for the feature pipeline.
struct Opponent {
  std::vector<Plane> channels;
  Plane luminance;
};

// `linear`: the values are linear already (HDR-FLIP's tone-mapped exposures), not sRGB-encoded.
Opponent opponent(const float* srgb, size_t width, size_t height, const Colour& colour, bool linear) {
  Opponent o{{Plane(width, height), Plane(width, height), Plane(width, height)}, Plane(width, height)};
  for (size_t i = 0; i < width * height; ++i) {
    const auto decode = [linear](float v) { return linear ? std::clamp(double(v), 0.0, 1.0) : srgb_to_linear(v); };
    const glm::dvec3 rgb(decode(srgb[3 * i]), decode(srgb[3 * i + 1]), decode(srgb[3 * i + 2]));
    const glm::dvec3 c = colour.ycxcz(rgb);
    for (int k = 0; k < 3; ++k) o.channels[size_t(k)].v[i] = c[k];
    o.luminance.v[i] = (c.x + 16) / 116;
  }
  return o;
}

// The opponent channels filtered by their contrast sensitivity, at the rows `rows`.
struct Filtered {
  Plane y, cx, cz;
};

Filtered filtered(const Opponent& o, double ppd, Rows rows) {
  return {csf_filter(o.channels[0], kAchromatic, ppd, rows), csf_filter(o.channels[1], kRedGreen, ppd, rows),
          csf_filter(o.channels[2], kBlueYellow, ppd, rows)};
}

// A filtered colour in Hunt-adjusted L*a*b*, first brought back into the RGB cube.
glm::dvec3 filtered_lab(const Filtered& f, size_t i, const Colour& colour) {
  return colour.hunt_lab(glm::clamp(colour.rgb_of_ycxcz({f.y.v[i], f.cx.v[i], f.cz.v[i]}), 0.0, 1.0));
}

// Every filter reaches this many rows above and below a pixel: the CSF's radius or the feature kernels'.
size_t halo_rows(double ppd) {
  const double csf = std::ceil(3 * std::sqrt(kWidestB / (2 * kPi * kPi)) * ppd);
  const double feature = std::ceil(3 * 0.5 * kEdgeWidthDegrees * ppd);
  return size_t(std::max(csf, feature));
}

// Output rows per band: about 256k pixels, so that a band's planes stay within some tens of megabytes.
size_t band_rows(size_t width, size_t height, const FlipOptions& options) {
  const size_t rows = options.band_rows ? options.band_rows : std::clamp<size_t>((size_t(1) << 18) / std::max<size_t>(width, 1), 16, 256);
  return std::min(rows, std::max<size_t>(height, 1));
}

// The part of the images that is computed: a rectangle [x0, x1) × [y0, y1) of output pixels, and the
// columns [cx0, cx1) its filters read.
struct Region {
  size_t x0 = 0, x1 = 0, y0 = 0, y1 = 0, cx0 = 0, cx1 = 0;
  bool empty() const { return x0 >= x1 || y0 >= y1; }
};

// Where ΔE may be other than 0: within `halo` pixels of a pixel that differs. Beyond, every filter sees the
// same values in both images, so HyAB and the feature difference are exactly 0 and so is ΔE (0^0.7 = 0,
// 0^1 = 0): those pixels are not computed, which in a render that changed in one place is most of them.
Region region_that_differs(const float* a, const float* b, size_t width, size_t height, size_t halo, bool whole) {
  Region r;
  if (whole) {
    r = {0, width, 0, height, 0, width};
  } else {
    size_t x0 = width, x1 = 0, y0 = height, y1 = 0;
    for (size_t y = 0; y < height; ++y) {
      const float* ra = a + 3 * width * y;
      const float* rb = b + 3 * width * y;
      if (std::equal(ra, ra + 3 * width, rb)) continue;
      y0 = std::min(y0, y), y1 = y + 1;
      size_t first = 0, last = width;
      while (first < width && std::equal(ra + 3 * first, ra + 3 * first + 3, rb + 3 * first)) ++first;
      while (last > first && std::equal(ra + 3 * (last - 1), ra + 3 * last, rb + 3 * (last - 1))) --last;
      x0 = std::min(x0, first), x1 = std::max(x1, last);
    }
    if (y0 >= y1) return r;
    r.x0 = x0 > halo ? x0 - halo : 0, r.x1 = std::min(width, x1 + halo);
    r.y0 = y0 > halo ? y0 - halo : 0, r.y1 = std::min(height, y1 + halo);
  }
  // The columns the outputs' filters reach; where that is the image's edge, the border rule repeats it as
  // for the whole image, and elsewhere the region's own edge is never reached by a kept output.
  r.cx0 = r.x0 > halo ? r.x0 - halo : 0, r.cx1 = std::min(width, r.x1 + halo);
  return r;
}

// Rows [first − halo, first + rows + halo) of an interleaved RGB image, columns [cx0, cx1), rows beyond
// the image's edges repeated as the filters' border rule repeats them: the band's filtered inner rows
// equal the whole image's, bit for bit.
std::vector<float> band_with_halo(const float* srgb, size_t width, size_t height, size_t first, size_t rows,
                                  size_t halo, const Region& region) {
  const size_t columns = region.cx1 - region.cx0;
  std::vector<float> band(3 * columns * (rows + 2 * halo));
  for (size_t r = 0; r < rows + 2 * halo; ++r) {
    const size_t y = size_t(std::clamp(long(first + r) - long(halo), 0L, long(height) - 1));
    std::copy_n(srgb + 3 * (width * y + region.cx0), 3 * columns, band.begin() + long(3 * columns * r));
  }
  return band;
}

// ΔE = ΔE_c ^ (1 − ΔE_f) of the band's inner rows (it has `halo` more each side), columns
// [keep, keep + kept) of its `width`, into rows of `error` `stride` apart. Only those pixels are filtered
// along y and measured; the halo is filtered along x for them.
void flip_band(const float* ref_band, const float* test_band, size_t width, size_t rows, size_t halo, double ppd,
               bool linear, const Colour& colour, size_t keep, size_t kept, double* error, size_t stride) {
  const size_t band_height = rows + 2 * halo;
  const Opponent ref = opponent(ref_band, width, band_height, colour, linear);
  const Opponent test = opponent(test_band, width, band_height, colour, linear);

  // The colour difference: HyAB^q_c, remapped against the largest one, green against blue.
  const double c_max = std::pow(hyab(colour.hunt_lab({0, 1, 0}), colour.hunt_lab({0, 0, 1})), kQc);
  const Rows inner{halo, halo + rows};
  const Filtered filtered_ref = filtered(ref, ppd, inner), filtered_test = filtered(test, ppd, inner);

  const FeatureKernels kernels = feature_kernels(ppd);
  const Features f_ref = features(ref.luminance, kernels, inner);
  const Features f_test = features(test.luminance, kernels, inner);

  for (size_t o = 0; o < rows * kept; ++o) {
    const size_t i = (halo + o / kept) * width + keep + o % kept;  // the same pixel in the band's planes
    const double feature_difference = std::max(std::abs(f_ref.edges.v[i] - f_test.edges.v[i]),
                                               std::abs(f_ref.points.v[i] - f_test.points.v[i]));
    double* out = &error[(o / kept) * stride + o % kept];
    // The same filtered colour and features: HyAB is 0, so ΔE = 0^(1 − 0) = 0, without the cube roots and
    // powers (in a crop around a local change, many pixels are so).
    if (feature_difference == 0 && filtered_ref.y.v[i] == filtered_test.y.v[i] &&
        filtered_ref.cx.v[i] == filtered_test.cx.v[i] && filtered_ref.cz.v[i] == filtered_test.cz.v[i]) {
      *out = 0;
      continue;
    }
    const double e = std::pow(hyab(filtered_lab(filtered_ref, i, colour), filtered_lab(filtered_test, i, colour)), kQc);
    const double colour_error = e < kPc * c_max ? kPt / (kPc * c_max) * e
                                                : kPt + (e - kPc * c_max) / (c_max - kPc * c_max) * (1 - kPt);
    const double feature_error = std::sqrt(feature_difference / std::numbers::sqrt2);  // ^q_f, q_f = 1/2
    *out = std::pow(colour_error, 1 - feature_error);
  }
}

// Doubles one band holds per pixel of its rows (with the halo) at its peak: two opponent images (four
// planes each), two filtered L*a*b* images (three each), four feature planes, and the filters'
// intermediate planes.
constexpr uint64_t kBandPlanes = 8 + 6 + 4 + 6;

}  // namespace

double pixels_per_degree(double distance_m, double width_px, double width_m) {
  return distance_m * (width_px / width_m) * (kPi / 180);
}

uint64_t flip_working_bytes(size_t width, size_t height, const FlipOptions& options) {
  const size_t rows = band_rows(width, height, options), halo = halo_rows(options.ppd);
  const uint64_t band_pixels = uint64_t(width) * (rows + 2 * halo);
  const uint64_t per_band = band_pixels * (kBandPlanes * sizeof(double) + 2 * 3 * sizeof(float));
  const uint64_t bands = (height + rows - 1) / std::max<size_t>(rows, 1);
  return per_band * std::min<uint64_t>(std::max(1u, options.threads), std::max<uint64_t>(bands, 1));
}

std::vector<double> flip_error_map(const float* reference_srgb, const float* test_srgb, size_t width, size_t height,
                                   const FlipOptions& options) {
  std::vector<double> error(width * height, 0.0);
  const size_t halo = halo_rows(options.ppd);
  const Region region = region_that_differs(reference_srgb, test_srgb, width, height, halo, !options.skip_equal);
  if (region.empty()) return error;
  const Colour colour;
  const size_t columns = region.cx1 - region.cx0, out_rows = region.y1 - region.y0;
  const size_t rows = band_rows(columns, out_rows, options);
  const size_t bands = (out_rows + rows - 1) / rows;
  concurrency::parallel_for(bands, options.threads, [&](size_t band) {
    const size_t first = region.y0 + band * rows, count = std::min(rows, region.y1 - first);
    const std::vector<float> ref = band_with_halo(reference_srgb, width, height, first, count, halo, region);
    const std::vector<float> test = band_with_halo(test_srgb, width, height, first, count, halo, region);
    struct Release {  // also when the band throws (out of memory)
      ~Release() { release_spare_planes(); }
    } release;
    flip_band(ref.data(), test.data(), columns, count, halo, options.ppd, options.linear_input, colour, region.x0 - region.cx0,
              region.x1 - region.x0, error.data() + first * width + region.x0, width);
  });
  return error;
}

namespace {

// HDR-FLIP's tone mapper: ACES as Narkowicz fits it, its 0.6 pre-exposure folded into the coefficients,
// t(x) = (k0 x² + k1 x + k2) / (k3 x² + k4 x + k5), clamped to [0, 1].
constexpr double kAces[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};
constexpr double kExposureTarget = 0.85;  // the brightest pixel at the first exposure, the median at the last
constexpr int kMaxExposures = 64;

double aces(double x) {
  const double t = (kAces[0] * x * x + kAces[1] * x + kAces[2]) / (kAces[3] * x * x + kAces[4] * x + kAces[5]);
  return std::clamp(t, 0.0, 1.0);
}

// The exposure at which t(x) = 0.85: the positive root of (k0 − 0.85 k3) x² + (k1 − 0.85 k4) x + (k2 − 0.85 k5).
double aces_target_input() {
  const double a = kAces[0] - kExposureTarget * kAces[3], b = kAces[1] - kExposureTarget * kAces[4],
               c = kAces[2] - kExposureTarget * kAces[5];
  return (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a);
}

double luminance709(const float* rgb) { return 0.2126 * double(rgb[0]) + 0.7152 * double(rgb[1]) + 0.0722 * double(rgb[2]); }

}  // namespace

HdrExposures hdr_exposures(const float* reference_rgb, size_t pixels) {
  // Infinite and NaN pixels say nothing about the range a person would look at: left out.
  std::vector<double> y;
  y.reserve(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    const double v = luminance709(reference_rgb + 3 * i);
    if (std::isfinite(v)) y.push_back(std::max(0.0, v));
  }
  pixels = y.size();
  HdrExposures e;
  if (y.empty()) return e;
  const double brightest = *std::max_element(y.begin(), y.end());
  std::nth_element(y.begin(), y.begin() + long(pixels / 2), y.end());
  double median = y[pixels / 2];  // the upper median, as the authors' tool takes it
  if (!(brightest > 0)) return e;  // a black reference: no exposure shows anything; one pair at 0
  if (!(median > 0)) median = brightest;  // mostly black: the range collapses onto the brightest pixel
  const double target = aces_target_input();
  e.start = std::log2(target / brightest);
  e.stop = std::log2(target / median);
  // One exposure per stop, at least two; at most kMaxExposures (a reference from 1e38 down to a denormal
  // would ask for hundreds of full passes), spread over the same range.
  e.count = int(std::clamp(std::ceil(e.stop - e.start), 2.0, double(kMaxExposures)));
  return e;
}

std::vector<double> hdr_flip_error_map(const float* reference_rgb, const float* test_rgb, size_t width, size_t height,
                                       const FlipOptions& options, HdrExposures* used) {
  const size_t pixels = width * height;
  const HdrExposures e = hdr_exposures(reference_rgb, pixels);
  if (used) *used = e;
  std::vector<double> error(pixels, 0.0);
  FlipOptions ldr = options;
  ldr.linear_input = true;
  std::vector<float> ref(3 * pixels), test(3 * pixels);
  for (int i = 0; i < e.count; ++i) {
    const double c = e.count > 1 ? e.start + i * (e.stop - e.start) / (e.count - 1) : e.start;
    const double scale = std::exp2(c);
    for (size_t k = 0; k < 3 * pixels; ++k) {
      // Negative and NaN light is no light; infinite light is white (ACES of infinity would be inf / inf).
      const auto shown = [scale](float v) {
        if (std::isnan(v) || v <= 0) return 0.0f;
        const double x = scale * double(v);
        return std::isfinite(x) ? float(aces(x)) : 1.0f;
      };
      ref[k] = shown(reference_rgb[k]);
      test[k] = shown(test_rgb[k]);
    }
    const std::vector<double> at = flip_error_map(ref.data(), test.data(), width, height, ldr);
    for (size_t k = 0; k < pixels; ++k)
      if (!(at[k] <= error[k])) error[k] = at[k];  // a NaN would be kept, never hidden
  }
  return error;
}

FlipPool pool_flip(const std::vector<double>& errors) {
  FlipPool pool;
  if (errors.empty()) return pool;
  double total = 0;
  for (double e : errors) total += e;
  pool.mean = total / double(errors.size());
  // Zeros add nothing to the running sum, so the weighted quartiles are among the other values: only
  // those are sorted (in a render that changed in one place, a small part of the image).
  std::vector<double> sorted;
  std::copy_if(errors.begin(), errors.end(), std::back_inserter(sorted), [](double e) { return e != 0; });
  std::sort(sorted.begin(), sorted.end());
  if (sorted.empty()) return pool;
  pool.min = sorted.size() < errors.size() ? 0.0 : sorted.front();
  pool.max = sorted.back();
  const auto weighted = [&](double p) {
    double running = 0;
    for (double e : sorted) {
      running += e;
      if (running > p * total) return e;
    }
    return sorted.back();
  };
  pool.q1 = weighted(0.25);
  pool.weighted_median = weighted(0.5);
  pool.q3 = weighted(0.75);
  return pool;
}

}  // namespace dqskin
