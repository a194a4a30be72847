// An image's pixels read as float a band of rows at a time (internal to lib/diff: the image diff and the
// bake diff's EXR textures). The band is read in the file's own formats and converted here, so that
// reading takes the caller's memory and one band, whatever the file: OpenImageIO's read_image converts
// through a buffer of its own of at least 64 MiB, or 256 rows however wide they are, which a few bytes of
// header can make any size.
#pragma once

#include <OpenImageIO/imageio.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace dqskin::diff_detail {

// Pixels of `spec`: width × height × depth, saturating at UINT64_MAX.
uint64_t pixel_count(const OIIO::ImageSpec& spec);

// Bytes of `spec`'s pixels as float: width × height × depth × channels × 4, saturating at UINT64_MAX.
uint64_t float_bytes(const OIIO::ImageSpec& spec);

// Bytes read_float_bands takes besides what `take` keeps: one band in the file's formats and as float,
// and one tile for a tiled file (read_float_image takes less: no band of floats). Saturating.
uint64_t band_bytes(const OIIO::ImageSpec& spec);

// Receives `pixels` pixels of `channels` interleaved floats each, starting at pixel number `first` (x
// fastest, then y, then z), in order.
using BandSink = std::function<void(const float* values, size_t first, size_t pixels)>;

// Reads the subimage `in` is at (its spec()) band by band, converted to float as read_image would
// (8-bit 255 is 1.0), and hands each band to `take`. Returns "" or why it cannot, in OpenImageIO's words
// (not yet made printable). Exceptions of `take` and std::bad_alloc pass through.
std::string read_float_bands(OIIO::ImageInput& in, const BandSink& take);

// The same converted straight into `pixels`, which holds pixel_count × channels floats (no band of floats
// is taken then).
std::string read_float_image(OIIO::ImageInput& in, float* pixels);

}  // namespace dqskin::diff_detail
