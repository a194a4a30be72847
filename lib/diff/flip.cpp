#include "flip.hpp"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
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
constexpr double kEdgeWidthDegrees = 0.082, kQf = 0.5;

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

double hyab(const glm::dvec3& a, const glm::dvec3& b) {
  return std::abs(a.x - b.x) + std::hypot(a.y - b.y, a.z - b.z);
}

double srgb_to_linear(float encoded) {
  const double c = std::clamp(double(encoded), 0.0, 1.0);
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// An image plane, row by row.
struct Plane {
  size_t width = 0, height = 0;
  std::vector<double> v;
  Plane(size_t w, size_t h) : width(w), height(h), v(w * h) {}
};

// Correlates along rows (horizontal) or columns with an odd kernel centred on its middle, the border
// pixels repeated beyond the edge. Rows go through a padded copy and columns are summed a whole row at a
// time, so that the inner loops run over contiguous memory without a clamp per tap.
Plane correlate(const Plane& in, const std::vector<double>& kernel, bool horizontal) {
  Plane out(in.width, in.height);
  const size_t r = kernel.size() / 2, w = in.width, h = in.height;
  if (horizontal) {
    std::vector<double> padded(w + 2 * r);
    for (size_t y = 0; y < h; ++y) {
      const double* row = &in.v[y * w];
      for (size_t i = 0; i < padded.size(); ++i) padded[i] = row[std::clamp(i, r, r + w - 1) - r];
      double* dst = &out.v[y * w];
      for (size_t x = 0; x < w; ++x) {
        double sum = 0;
        for (size_t k = 0; k < kernel.size(); ++k) sum += kernel[k] * padded[x + k];
        dst[x] = sum;
      }
    }
  } else {
    for (size_t y = 0; y < h; ++y) {
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

Plane separable(const Plane& in, const std::vector<double>& along_x, const std::vector<double>& along_y) {
  return correlate(correlate(in, along_x, true), along_y, false);
}

// Colour pipeline, spatial filtering: the CSF's spatial kernel, a1 √(π/b1) e^(−π² r²/b1) + a2 √(π/b2)
// e^(−π² r²/b2) with r in degrees, sampled at the pixels within three standard deviations of the widest
// Gaussian of all channels and normalized to sum 1. Each Gaussian term is separable, so the 2-D kernel is
// applied as one pass along x and one along y per term.
Plane csf_filter(const Plane& channel, const Csf& csf, double ppd) {
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
    const Plane pass = separable(channel, t.g, t.g);
    for (size_t i = 0; i < out.v.size(); ++i) out.v[i] += t.weight / total * pass.v[i];
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

Features features(const Plane& luminance, const FeatureKernels& k) {
  const Plane smoothed_along_x = correlate(luminance, k.gaussian, true);  // shared by both detectors' y response
  const auto magnitude = [&](const std::vector<double>& d) {
    const Plane dx = correlate(correlate(luminance, d, true), k.gaussian, false);
    const Plane dy = correlate(smoothed_along_x, d, false);
    Plane m(luminance.width, luminance.height);
    for (size_t i = 0; i < m.v.size(); ++i) m.v[i] = std::hypot(dx.v[i], dy.v[i]);
    return m;
  };
  return {magnitude(k.edge), magnitude(k.point)};
}

// One image in opponent space (three planes) and its luminance Y / Y_white for the feature pipeline.
struct Opponent {
  std::vector<Plane> channels;
  Plane luminance;
};

Opponent opponent(const float* srgb, size_t width, size_t height, const Colour& colour) {
  Opponent o{{Plane(width, height), Plane(width, height), Plane(width, height)}, Plane(width, height)};
  for (size_t i = 0; i < width * height; ++i) {
    const glm::dvec3 rgb(srgb_to_linear(srgb[3 * i]), srgb_to_linear(srgb[3 * i + 1]), srgb_to_linear(srgb[3 * i + 2]));
    const glm::dvec3 c = colour.ycxcz(rgb);
    for (int k = 0; k < 3; ++k) o.channels[size_t(k)].v[i] = c[k];
    o.luminance.v[i] = (c.x + 16) / 116;
  }
  return o;
}

// The filtered colours in Hunt-adjusted L*a*b*, each first brought back into the RGB cube.
std::vector<glm::dvec3> filtered_lab(const Opponent& o, double ppd, const Colour& colour) {
  const Plane y = csf_filter(o.channels[0], kAchromatic, ppd);
  const Plane cx = csf_filter(o.channels[1], kRedGreen, ppd);
  const Plane cz = csf_filter(o.channels[2], kBlueYellow, ppd);
  std::vector<glm::dvec3> lab(y.v.size());
  for (size_t i = 0; i < lab.size(); ++i)
    lab[i] = colour.hunt_lab(glm::clamp(colour.rgb_of_ycxcz({y.v[i], cx.v[i], cz.v[i]}), 0.0, 1.0));
  return lab;
}

}  // namespace

double pixels_per_degree(double distance_m, double width_px, double width_m) {
  return distance_m * (width_px / width_m) * (kPi / 180);
}

std::vector<double> flip_error_map(const float* reference_srgb, const float* test_srgb, size_t width, size_t height,
                                   double ppd) {
  const Colour colour;
  const Opponent ref = opponent(reference_srgb, width, height, colour);
  const Opponent test = opponent(test_srgb, width, height, colour);

  // The colour difference: HyAB^q_c, remapped against the largest one, green against blue.
  const double c_max = std::pow(hyab(colour.hunt_lab({0, 1, 0}), colour.hunt_lab({0, 0, 1})), kQc);
  const std::vector<glm::dvec3> lab_ref = filtered_lab(ref, ppd, colour);
  const std::vector<glm::dvec3> lab_test = filtered_lab(test, ppd, colour);

  const FeatureKernels kernels = feature_kernels(ppd);
  const Features f_ref = features(ref.luminance, kernels);
  const Features f_test = features(test.luminance, kernels);

  std::vector<double> error(width * height);
  for (size_t i = 0; i < error.size(); ++i) {
    const double e = std::pow(hyab(lab_ref[i], lab_test[i]), kQc);
    const double colour_error = e < kPc * c_max ? kPt / (kPc * c_max) * e
                                                : kPt + (e - kPc * c_max) / (c_max - kPc * c_max) * (1 - kPt);
    const double feature_difference = std::max(std::abs(f_ref.edges.v[i] - f_test.edges.v[i]),
                                               std::abs(f_ref.points.v[i] - f_test.points.v[i]));
    const double feature_error = std::pow(feature_difference / std::numbers::sqrt2, kQf);
    error[i] = std::pow(colour_error, 1 - feature_error);
  }
  return error;
}

FlipPool pool_flip(const std::vector<double>& errors) {
  FlipPool pool;
  if (errors.empty()) return pool;
  std::vector<double> sorted = errors;
  std::sort(sorted.begin(), sorted.end());
  double total = 0;
  for (double e : errors) total += e;
  pool.mean = total / double(errors.size());
  pool.min = sorted.front();
  pool.max = sorted.back();
  const auto weighted = [&](double p) {
    double running = 0;
    for (double e : sorted) {
      running += e;
      if (running > p * total) return e;
    }
    return sorted.back();
  };
  if (total > 0) {
    pool.q1 = weighted(0.25);
    pool.weighted_median = weighted(0.5);
    pool.q3 = weighted(0.75);
  }
  return pool;
}

}  // namespace dqskin
