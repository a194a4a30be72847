// FLIP, the perceptual difference of two LDR images as a person sees them alternate (Andersson, Nilsson,
// Akenine-Möller, Oskarsson, Åström and Fairchild, "FLIP: A Difference Evaluator for Alternating Images",
// PACMCGIT 3(2), 2020): per pixel a value from 0 (no visible difference) to 1, from a colour pipeline
// (contrast-sensitivity filtering in an opponent space, Hunt-adjusted L*a*b*, the HyAB distance) and a
// feature pipeline (edges and points on luminance), ΔE = ΔE_c ^ (1 − ΔE_f). Computed in double precision;
// the authors' tools use float, which moves their means by up to about 5e-5 (they sum in float too).
// Internal to lib/diff: `dqskin diff --metric flip` (image_diff.hpp) is its interface.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace dqskin {

// Pixels per degree of visual angle for an observer `distance_m` metres from a monitor `width_m` metres
// wide showing `width_px` pixels across (small-angle form, as the paper's viewing conditions). The
// paper's default, 0.7 m from a 0.7 m wide 3840-pixel monitor, gives 67.02.
double pixels_per_degree(double distance_m, double width_px, double width_m);
inline constexpr double kDefaultPixelsPerDegree = 67.02064327658226;  // 3840 π / 180

struct FlipOptions {
  double ppd = kDefaultPixelsPerDegree;  // the viewing conditions: pixels per degree of visual angle
  unsigned threads = 1;                  // bands of rows computed at once
  size_t band_rows = 0;                  // output rows per band; 0: about 256k pixels' worth (tests set it)
  // Compute only within reach of the pixels that differ (elsewhere ΔE is exactly 0); false computes every
  // pixel, which gives the same values (the tests compare both).
  bool skip_equal = true;
  // The inputs are linear RGB in [0, 1], not sRGB-encoded (HDR-FLIP's tone-mapped exposures).
  bool linear_input = false;
};

// Two images of width × height pixels, interleaved RGB of sRGB-encoded display values from 0 to 1 (as an
// 8-bit PNG reads, v / 255); values outside are clamped. Returns ΔE per pixel, row by row. Computed in
// bands of rows, each with the rows its filters reach beyond it, on up to options.threads threads: the
// result is the same, bit for bit, whatever the band size, thread count and skip_equal.
std::vector<double> flip_error_map(const float* reference_srgb, const float* test_srgb, size_t width, size_t height,
                                   const FlipOptions& options = {});

// HDR-FLIP (Andersson, Nilsson, Shirley and Akenine-Möller, "Visualizing Errors in Rendered High Dynamic
// Range Images", Eurographics 2021 short papers): both images tone-mapped (ACES, Narkowicz's fit) at
// exposures 2^c for c evenly spaced from `start`, where the reference's brightest pixel (Rec. 709
// luminance) maps to 0.85, to `stop`, where its median pixel does, `count` = max(2, ⌈stop − start⌉) of
// them; LDR-FLIP of each pair (the tone-mapped values linear); per pixel the largest. Inputs are interleaved
// linear RGB of any range (negative and NaN as 0).
struct HdrExposures {
  double start = 0, stop = 0;
  int count = 2;
};
HdrExposures hdr_exposures(const float* reference_rgb, size_t pixels);
std::vector<double> hdr_flip_error_map(const float* reference_rgb, const float* test_rgb, size_t width, size_t height,
                                       const FlipOptions& options = {}, HdrExposures* used = nullptr);

// The most memory flip_error_map holds beside its inputs and its result (the bands being computed).
uint64_t flip_working_bytes(size_t width, size_t height, const FlipOptions& options);

// The figures FLIP's tools report for an error map: the mean, the weighted quartiles (each pixel weighted
// by its own error: the smallest value at which the ascending running sum exceeds p of the total), the
// extremes.
struct FlipPool {
  double mean = 0, q1 = 0, weighted_median = 0, q3 = 0, min = 0, max = 0;
};
FlipPool pool_flip(const std::vector<double>& errors);

}  // namespace dqskin
