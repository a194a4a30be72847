// FLIP on cases whose value follows from the paper's equations, and on hand-made images against an
// independent implementation written from the paper (a NumPy prototype in double precision; its figures,
// printed to 6 or 7 digits, are the expected values below, so the tolerance is 1e-6).
#include "flip.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

namespace dqskin {
namespace {

struct Image {
  size_t width, height;
  std::vector<float> rgb;
  Image(size_t w, size_t h, float value) : width(w), height(h), rgb(3 * w * h, value) {}
  void set(size_t x, size_t y, float value) { std::fill_n(rgb.begin() + long(3 * (y * width + x)), 3, value); }
};

std::vector<double> flip(const Image& reference, const Image& test) {
  return flip_error_map(reference.rgb.data(), test.rgb.data(), reference.width, reference.height);
}

double mean(const std::vector<double>& v) {
  double sum = 0;
  for (double e : v) sum += e;
  return sum / double(v.size());
}

// Deterministic noise from 0 to 1 (a linear congruential generator: the same pixels on every machine).
Image noise(size_t w, size_t h, uint32_t seed) {
  Image image(w, h, 0);
  for (float& v : image.rgb) {
    seed = seed * 1664525u + 1013904223u;
    v = float(seed >> 8) / float(1u << 24);
  }
  return image;
}

TEST(Flip, PixelsPerDegreeOfThePapersViewingConditions) {
  // 0.7 m from a 0.7 m wide monitor of 3840 pixels: 3840 π / 180.
  EXPECT_NEAR(pixels_per_degree(0.7, 3840, 0.7), 3840 * std::numbers::pi / 180, 1e-12);
  EXPECT_NEAR(pixels_per_degree(0.7, 3840, 0.7), kDefaultPixelsPerDegree, 1e-12);
}

TEST(Flip, IdenticalImagesAreZeroEverywhere) {
  const Image image = noise(40, 30, 7);
  for (double e : flip(image, image)) ASSERT_EQ(e, 0.0);
}

TEST(Flip, AUniformGreyShiftIsTheColourPipelineAlone) {
  // A constant image is its own filtered image and has no edges or points, so ΔE_f = 0 and ΔE = ΔE_c.
  // For greys a* = b* = 0 and the HyAB distance is |ΔL*|, with L* = 116 Y^(1/3) − 16 and Y the linear
  // value (the XYZ matrix's Y row sums to 1). c_max = HyAB(green, blue)^0.7 = 203.301655^0.7.
  const auto lightness = [](double srgb) { return 116 * std::cbrt(std::pow((srgb + 0.055) / 1.055, 2.4)) - 16; };
  const double e = std::pow(lightness(0.55) - lightness(0.5), 0.7);
  const double c_max = std::pow(203.301655, 0.7);
  const double expected = 0.95 / (0.4 * c_max) * e;  // below 0.4 c_max: the first, linear part of the map
  EXPECT_NEAR(expected, 0.176461, 1e-6);             // the prototype's value
  for (double v : flip(Image(32, 32, 0.5f), Image(32, 32, 0.55f))) ASSERT_NEAR(v, expected, 1e-6);
}

TEST(Flip, OneChangedPixel) {
  Image reference(64, 64, 0), test(64, 64, 0);
  test.set(32, 32, 1);
  const std::vector<double> error = flip(reference, test);
  const auto worst = std::max_element(error.begin(), error.end());
  EXPECT_EQ(worst - error.begin(), 32 * 64 + 32);  // at the pixel itself
  EXPECT_NEAR(*worst, 0.864906, 1e-6);
  EXPECT_NEAR(mean(error), 0.0034940, 1e-6);
  EXPECT_EQ(error[0], 0.0);  // beyond both filters' reach nothing differs
}

TEST(Flip, AnEdgeMovedByOnePixel) {
  Image reference(64, 64, 0), test(64, 64, 0);
  for (size_t y = 0; y < 64; ++y)
    for (size_t x = 0; x < 64; ++x) {
      if (x >= 32) reference.set(x, y, 1);
      if (x >= 31) test.set(x, y, 1);
    }
  const std::vector<double> error = flip(reference, test);
  EXPECT_NEAR(*std::max_element(error.begin(), error.end()), 0.772916, 1e-6);
  EXPECT_NEAR(mean(error), 0.051723, 1e-6);
}

TEST(Flip, TheSameBothWaysAndWithinZeroAndOne) {
  const Image a = noise(33, 21, 1), b = noise(33, 21, 2);
  const std::vector<double> ab = flip(a, b), ba = flip(b, a);
  EXPECT_EQ(ab, ba);
  for (double e : ab) {
    ASSERT_GE(e, 0.0);
    ASSERT_LE(e, 1.0);
  }
}

TEST(Flip, BandsAndThreadsGiveTheWholeImagesValuesBitForBit) {
  // The filters reach about 10 rows at 67 pixels per degree: bands of 1, 7 and 16 rows each need rows of
  // their neighbours, and the image's top and bottom bands its repeated border rows.
  const Image a = noise(37, 45, 3), b = noise(37, 45, 4);
  const std::vector<double> whole = flip_error_map(a.rgb.data(), b.rgb.data(), 37, 45, {kDefaultPixelsPerDegree, 1, 45});
  for (size_t rows : {size_t(1), size_t(7), size_t(16)})
    for (unsigned threads : {1u, 3u})
      EXPECT_EQ(flip_error_map(a.rgb.data(), b.rgb.data(), 37, 45, {kDefaultPixelsPerDegree, threads, rows}), whole)
          << rows << " rows per band, " << threads << " threads";
  // At 10 pixels per degree the filters are narrow: the figures change, not the banding's equality.
  const std::vector<double> near = flip_error_map(a.rgb.data(), b.rgb.data(), 37, 45, {10, 1, 45});
  EXPECT_NE(near, whole);
  EXPECT_EQ(flip_error_map(a.rgb.data(), b.rgb.data(), 37, 45, {10, 2, 4}), near);
}

TEST(Flip, OnlyTheReachOfTheChangedPixelsIsComputedWithTheSameValues) {
  // Two changes far apart in a 120 × 90 image, one near the right edge: everything beyond the filters'
  // reach of both is exactly 0, and the pixels within it are those of the whole computation.
  Image a = noise(120, 90, 5), b = a;
  b.set(20, 30, 0.9f);
  b.set(117, 70, 0.1f);
  FlipOptions whole{kDefaultPixelsPerDegree, 1, 0, false};
  const std::vector<double> expected = flip_error_map(a.rgb.data(), b.rgb.data(), 120, 90, whole);
  for (size_t rows : {size_t(0), size_t(5)})
    for (unsigned threads : {1u, 2u})
      EXPECT_EQ(flip_error_map(a.rgb.data(), b.rgb.data(), 120, 90, {kDefaultPixelsPerDegree, threads, rows, true}), expected)
          << rows << " rows per band, " << threads << " threads";
  EXPECT_EQ(expected[0], 0.0);
  EXPECT_GT(expected[30 * 120 + 25], 0.0);  // within reach of a change
  const Image same = noise(50, 40, 9);
  for (double e : flip_error_map(same.rgb.data(), same.rgb.data(), 50, 40)) ASSERT_EQ(e, 0.0);
}

TEST(Flip, WorkingMemoryGrowsWithThreadsNotHeight) {
  const FlipOptions one{kDefaultPixelsPerDegree, 1, 0}, four{kDefaultPixelsPerDegree, 4, 0};
  EXPECT_EQ(flip_working_bytes(2048, 2048, one), flip_working_bytes(2048, 8192, one));
  EXPECT_EQ(flip_working_bytes(2048, 2048, four), 4 * flip_working_bytes(2048, 2048, one));
  // The whole image at once would hold some 24 planes of doubles (800 MB at 2048²); one band an eighth of that.
  EXPECT_LT(flip_working_bytes(2048, 2048, one), uint64_t(2048) * 2048 * 24 * 8 / 8);
}

// ACES as HDR-FLIP uses it (Narkowicz's fit with its 0.6 pre-exposure folded in), written out again here.
double aces(double x) {
  const double t = (0.9036 * x * x + 0.018 * x) / (0.8748 * x * x + 0.354 * x + 0.14);
  return std::clamp(t, 0.0, 1.0);
}

TEST(HdrFlip, ExposuresSpanTheReferencesBrightestToItsMedianPixel) {
  // Greys 1, 4 and 16 (R = G = B, so Rec. 709 luminance is the value): the brightest pixel maps to 0.85 at
  // the first exposure and the (upper) median at the last; ACES reaches 0.85 at x = 2.1188723.
  const std::vector<float> rgb = {4, 4, 4, 16, 16, 16, 1, 1, 1};
  const HdrExposures e = hdr_exposures(rgb.data(), 3);
  const double x_t = std::exp2(e.start) * 16;
  EXPECT_NEAR(x_t, 2.1188723, 1e-7);
  EXPECT_NEAR(aces(x_t), 0.85, 1e-12);
  EXPECT_NEAR(e.stop - e.start, 2.0, 1e-12);  // log2(16 / 4)
  EXPECT_EQ(e.count, 2);
  const std::vector<float> wide = {1e-3f, 1e-3f, 1e-3f, 1e-3f, 1e-3f, 1e-3f, 100, 100, 100};
  EXPECT_EQ(hdr_exposures(wide.data(), 3).count, 17);  // ⌈log2(1e5)⌉
}

TEST(HdrFlip, AUniformShiftIsTheColourPipelineAtTheExposureThatShowsIt) {
  // A uniform grey L against 1.25 L: one exposure (start = stop) puts the reference at 0.85, the test at
  // ACES(1.25 x_t); both are linear greys, so ΔE = ΔE_c of their L* = 116 Y^(1/3) − 16.
  const double x_t = 2.1188723;
  const auto lightness = [](double y) { return 116 * std::cbrt(y) - 16; };
  const double c_max = std::pow(203.301655, 0.7);
  const double e = std::pow(std::abs(lightness(aces(1.25 * x_t)) - lightness(0.85)), 0.7);
  const double expected = e < 0.4 * c_max ? 0.95 / (0.4 * c_max) * e : 0.95 + (e - 0.4 * c_max) / (0.6 * c_max) * 0.05;
  Image a(24, 24, 3.0f), b(24, 24, 3.75f);
  HdrExposures used;
  const std::vector<double> map = hdr_flip_error_map(a.rgb.data(), b.rgb.data(), 24, 24, {}, &used);
  EXPECT_EQ(used.count, 2);
  EXPECT_EQ(used.start, used.stop);
  for (double v : map) ASSERT_NEAR(v, expected, 2e-6);  // the tone-mapped values are floats
  EXPECT_GT(expected, 0.01);
  for (double v : hdr_flip_error_map(a.rgb.data(), a.rgb.data(), 24, 24)) ASSERT_EQ(v, 0.0);
}

TEST(HdrFlip, InfiniteAndNanLightNeitherHideNorSpreadAnError) {
  // An infinite pixel in the reference leaves the exposure range to the finite ones, and shows as white;
  // the difference elsewhere still counts. A NaN pixel is black.
  Image a(24, 24, 3.0f), b(24, 24, 3.0f);
  b.set(5, 5, 30.0f);
  const std::vector<double> plain = hdr_flip_error_map(a.rgb.data(), b.rgb.data(), 24, 24);
  a.set(20, 20, std::numeric_limits<float>::infinity());
  b.set(20, 20, std::numeric_limits<float>::infinity());
  HdrExposures e;
  const std::vector<double> with_inf = hdr_flip_error_map(a.rgb.data(), b.rgb.data(), 24, 24, {}, &e);
  EXPECT_TRUE(std::isfinite(e.start) && std::isfinite(e.stop));
  EXPECT_GT(with_inf[5 * 24 + 5], 0.05);
  for (double v : with_inf) ASSERT_TRUE(v >= 0 && v <= 1);
  EXPECT_EQ(with_inf[20 * 24 + 20], 0.0);  // white in both
  EXPECT_EQ(with_inf[5 * 24 + 5], plain[5 * 24 + 5]);  // the same exposures; (20, 20) is beyond the filters' reach
  Image nan_test = b;
  nan_test.set(20, 20, std::numeric_limits<float>::quiet_NaN());  // black against white: seen
  EXPECT_GT(hdr_flip_error_map(a.rgb.data(), nan_test.rgb.data(), 24, 24)[20 * 24 + 20], 0.2);
}

TEST(HdrFlip, ExposuresAreCappedForAnAbsurdRange) {
  const std::vector<float> rgb = {1e-30f, 1e-30f, 1e-30f, 1e-30f, 1e-30f, 1e-30f, 1e30f, 1e30f, 1e30f};
  EXPECT_EQ(hdr_exposures(rgb.data(), 3).count, 64);
}

TEST(Flip, PoolingWeighsEachPixelByItsError) {
  // Running sums of the sorted values 0.1, 0.3, 0.6, 1.0: the first above 0.25, 0.5 and 0.75 of the total.
  const FlipPool pool = pool_flip({0.4, 0.1, 0.3, 0.2});
  EXPECT_DOUBLE_EQ(pool.mean, 0.25);
  EXPECT_EQ(pool.q1, 0.2);
  EXPECT_EQ(pool.weighted_median, 0.3);
  EXPECT_EQ(pool.q3, 0.4);
  EXPECT_EQ(pool.min, 0.1);
  EXPECT_EQ(pool.max, 0.4);
  const FlipPool zero = pool_flip({0, 0});
  EXPECT_EQ(zero.weighted_median, 0.0);
}

}  // namespace
}  // namespace dqskin
