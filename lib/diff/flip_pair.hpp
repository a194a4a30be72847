// One image pair measured by FLIP for `dqskin diff --metric flip` (internal to lib/diff): the images as
// diff reads them (float, any channel count) brought to what FLIP takes, its error map, and the figures
// the reports and the verdict use.
#pragma once

#include "dqskin/image_diff.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace dqskin::diff_detail {

// How an image's floats are laid out and what they mean.
struct PixelLayout {
  size_t width = 0, height = 0, channels = 0;
  // True for float and half files (EXR, HDR): linear light, measured by HDR-FLIP; false for integer files
  // (PNG, JPEG, 8- and 16-bit TIFF), whose values are display values, measured by LDR-FLIP.
  bool linear = false;
};

// FLIP's input: interleaved RGB display values, from the first three channels (RGB; alpha and others
// ignored) or, for one or two channels, the first as grey. OpenImageIO has already multiplied colours by
// their alpha, so a transparent pixel is seen over black. Linear values are sRGB-encoded (clamped to
// [0, 1]); display values are kept (NaN as 0).
std::vector<float> flip_rgb(const float* pixels, const PixelLayout& layout);

// Measures the pair: fills d's metric, max_error and its place, mean and RMS error, FLIP's weighted
// quartiles, pixels and the counts over --warn and --fail (PSNR is NaN: FLIP has none), over the pixels
// `excluded` does not mark (none marked when it is empty; their values in the map are 0). Returns the
// error map, row by row.
std::vector<double> flip_pair(const float* a, const float* b, const PixelLayout& layout,
                              const std::vector<uint8_t>& excluded, const DiffOptions& options, ImageDiff& d);

// The most memory flip_pair holds beside the two images: both as FLIP's RGB, the error map, its sorted
// copy for the quartiles and the bands being computed.
// `hdr`: float files, whose HDR-FLIP also holds both tone-mapped exposures and one exposure's map.
uint64_t flip_pair_bytes(size_t width, size_t height, const DiffOptions& options, bool hdr);

}  // namespace dqskin::diff_detail
