#include "flip_pair.hpp"
#include "flip.hpp"
#include "../base/saturating.hpp"
#include "../base/srgb.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dqskin::diff_detail {
namespace {

FlipOptions flip_options(const DiffOptions& options) { return {options.pixels_per_degree, options.threads, 0}; }

}  // namespace

std::vector<float> flip_rgb(const float* pixels, const PixelLayout& layout) {
  const size_t count = layout.width * layout.height, channels = layout.channels;
  std::vector<float> rgb(3 * count);
  for (size_t i = 0; i < count; ++i)
    for (size_t c = 0; c < 3; ++c) {
      // NaN is not a display value: FLIP sees it as black, as a viewer would show it.
      const float v = pixels[i * channels + (channels >= 3 ? c : 0)];
      const float shown = std::isnan(v) ? 0.0f : v;
      rgb[3 * i + c] = layout.linear ? float(io::srgb_encode(double(shown))) : shown;
    }
  return rgb;
}

std::vector<double> flip_pair(const float* a, const float* b, const PixelLayout& layout,
                              const std::vector<uint8_t>& excluded, const DiffOptions& options, ImageDiff& d) {
  std::vector<double> errors;
  d.hdr_exposures = 0;
  if (layout.linear) {
    // Linear light: HDR-FLIP, over the exposures the reference's range needs.
    PixelLayout display = layout;
    display.linear = false;  // flip_rgb then keeps the values as they are
    const std::vector<float> ra = flip_rgb(a, display), rb = flip_rgb(b, display);
    HdrExposures e;
    errors = hdr_flip_error_map(ra.data(), rb.data(), layout.width, layout.height, flip_options(options), &e);
    d.hdr_exposures = e.count;
    d.hdr_start = e.start;
    d.hdr_stop = e.stop;
  } else {
    const std::vector<float> ra = flip_rgb(a, layout), rb = flip_rgb(b, layout);
    errors = flip_error_map(ra.data(), rb.data(), layout.width, layout.height, flip_options(options));
  }
  d.metric = DiffMetric::kFlip;
  d.psnr = std::numeric_limits<double>::quiet_NaN();
  d.max_channel.clear();
  // Left-out pixels are 0 in the map and outside the figures.
  std::vector<double> kept;
  if (!excluded.empty()) {
    kept.reserve(errors.size());
    for (size_t i = 0; i < errors.size(); ++i) {
      if (excluded[i]) errors[i] = 0;
      else kept.push_back(errors[i]);
    }
  }
  const std::vector<double>& measured = excluded.empty() ? errors : kept;
  d.pixels = uint64_t(measured.size());
  const FlipPool pool = pool_flip(measured);
  d.max_error = pool.max;
  d.mean_error = pool.mean;
  d.flip_q1 = pool.q1;
  d.flip_median = pool.weighted_median;
  d.flip_q3 = pool.q3;
  const auto worst = std::find(errors.begin(), errors.end(), pool.max);  // the first, in row order
  const size_t at = worst == errors.end() ? 0 : size_t(worst - errors.begin());
  d.max_x = pool.max > 0 ? int(at % layout.width) : 0;
  d.max_y = pool.max > 0 ? int(at / layout.width) : 0;
  double squares = 0;
  d.over_warn = d.over_fail = 0;
  for (double e : measured) {
    squares += e * e;
    d.over_warn += e > options.thresholds.warn;
    d.over_fail += e > options.thresholds.fail;
  }
  d.rms_error = measured.empty() ? 0 : std::sqrt(squares / double(measured.size()));
  return errors;
}

uint64_t flip_pair_bytes(size_t width, size_t height, const DiffOptions& options, bool hdr) {
  using saturating::add;
  using saturating::mul;
  const uint64_t pixels = mul(width, height);
  // Both images as RGB floats while the bands run; then the error map and the quartiles' sorted copy.
  uint64_t computing = add(mul(pixels, 2 * 3 * sizeof(float)), flip_working_bytes(width, height, flip_options(options)));
  if (hdr) computing = add(computing, mul(pixels, 2 * 3 * sizeof(float) + sizeof(double)));
  // With a mask: its mark per pixel, and the kept values copied out for the figures.
  const uint64_t masked = options.mask.empty() ? 0 : mul(pixels, 1 + sizeof(double));
  return add(add(mul(pixels, sizeof(double)), std::max(computing, mul(pixels, sizeof(double)))), masked);
}

}  // namespace dqskin::diff_detail
