// The picture of a FLIP error map (internal to lib/diff; written by the image module,
// flip_heat_map_oiio.cpp): each pixel's FLIP value in the magma colormap, as the FLIP paper shows its maps,
// with a fixed scale (black 0, light yellow 1: the same colour means the same visibility in every map) and
// the colour bar and its labels in a panel on the right, so that the file read alone says what it shows.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace dqskin::diff_detail {

// The picture's size: the map at the top left, the legend's panel to its right; at least tall enough for
// the legend (smaller maps get a dark margin below).
struct FlipHeatMapSize {
  int width = 0, height = 0, scale = 1;  // scale: font pixels per glyph pixel
};
FlipHeatMapSize flip_heat_map_size(size_t width, size_t height);

// Memory the picture takes while it is made (its float RGBA, the colours and the 8-bit file's pixels).
uint64_t flip_heat_map_bytes(size_t width, size_t height);

// Writes the picture of `errors` (width × height values from 0 to 1, row by row) to `path` as an 8-bit sRGB
// PNG, atomically, replacing an older file; the folders above it are created. Throws OutputError.
void write_flip_heat_map(const std::string& path, const std::vector<double>& errors, size_t width, size_t height);

}  // namespace dqskin::diff_detail
