#include "image_bands_oiio.hpp"

#include "../base/saturating.hpp"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <vector>

namespace dqskin::diff_detail {
namespace {

using saturating::mul;

// About 4 MiB of floats a band: large enough that a band is many rows (or a row of tiles) of a
// real image, small beside any --max-memory.
constexpr uint64_t kBandValues = uint64_t(1) << 20;

// Rows (of each slice) and slices a band holds.
struct Band {
  uint64_t rows = 1, slices = 1;
};

// Bands cover whole rows of tiles in a tiled file (read_tiles takes a tile-aligned region), and for a
// volume tiled in depth a whole slab, every row of tile_depth slices, so that each band is contiguous
// in pixel order.
Band band_of(const OIIO::ImageSpec& s) {
  Band band;
  const uint64_t row_values = std::max<uint64_t>(1, mul(uint64_t(s.width), uint64_t(s.nchannels)));
  band.rows = std::max<uint64_t>(1, kBandValues / row_values);
  if (s.tile_width > 0) {
    const uint64_t tile_rows = uint64_t(std::max(1, s.tile_height));
    band.rows = (band.rows + tile_rows - 1) / tile_rows * tile_rows;
    if (s.depth > 1 && s.tile_depth > 1) band.rows = uint64_t(s.height), band.slices = uint64_t(s.tile_depth);
  }
  band.rows = std::min<uint64_t>(band.rows, uint64_t(std::max(1, s.height)));
  band.slices = std::min<uint64_t>(band.slices, uint64_t(std::max(1, s.depth)));
  return band;
}

// The reading of read_float_bands and read_float_image: each band converted into `whole` at its place
// when it is given, else into a band of floats handed to `take`.
std::string read_bands(OIIO::ImageInput& in, float* whole, const BandSink* take) {
  const OIIO::ImageSpec spec = in.spec();
  const int subimage = in.current_subimage(), miplevel = in.current_miplevel();
  const size_t width = size_t(spec.width), channels = size_t(spec.nchannels);
  if (mul(width, channels) > uint64_t(INT_MAX)) return "its rows are too wide to read";
  const Band band = band_of(spec);
  const size_t native_pixel = spec.pixel_bytes(true);
  std::vector<unsigned char> native(size_t(band.rows * band.slices) * width * native_pixel);
  std::vector<float> values(whole ? 0 : size_t(band.rows * band.slices) * width * channels);
  const OIIO::TypeDesc kNative = OIIO::TypeDesc::UNKNOWN;  // read_* in the file's own formats: no copy of theirs
  size_t first = 0;
  for (int z = 0, zend = 0; z < spec.depth; z = zend) {
    zend = int(std::min<int64_t>(spec.depth, int64_t(z) + int64_t(band.slices)));
    for (int y = 0, yend = 0; y < spec.height; y = yend) {
      yend = int(std::min<int64_t>(spec.height, int64_t(y) + int64_t(band.rows)));
      const bool ok =
          spec.tile_width > 0
              ? in.read_tiles(subimage, miplevel, spec.x, spec.x + spec.width, spec.y + y, spec.y + yend, spec.z + z,
                              spec.z + zend, 0, spec.nchannels, kNative, native.data())
              : in.read_scanlines(subimage, miplevel, spec.y + y, spec.y + yend, spec.z + z, 0, spec.nchannels, kNative,
                                  native.data());
      if (!ok) return in.geterror();
      // As read_image converts: all channels at once, or one at a time when their formats differ.
      const int rows = (yend - y) * (zend - z);
      float* const out = whole ? whole + first * channels : values.data();
      bool converted = true;
      if (spec.channelformats.empty()) {
        converted = OIIO::convert_image(spec.nchannels, spec.width, rows, 1, native.data(), spec.format, OIIO::AutoStride,
                                        OIIO::AutoStride, OIIO::AutoStride, out, OIIO::TypeDesc::FLOAT,
                                        OIIO::AutoStride, OIIO::AutoStride, OIIO::AutoStride);
      } else {
        size_t offset = 0;
        for (size_t c = 0; c < channels && converted; ++c) {
          const OIIO::TypeDesc format = spec.channelformats[c];
          converted = OIIO::convert_image(1, spec.width, rows, 1, native.data() + offset, format,
                                          OIIO::stride_t(native_pixel), OIIO::AutoStride, OIIO::AutoStride,
                                          out + c, OIIO::TypeDesc::FLOAT, OIIO::stride_t(4 * channels),
                                          OIIO::AutoStride, OIIO::AutoStride);
          offset += format.size();
        }
      }
      if (!converted) return "OpenImageIO cannot convert its pixels to float";
      const size_t pixels = size_t(rows) * width;
      if (take) (*take)(values.data(), first, pixels);
      first += pixels;
    }
  }
  return "";
}

}  // namespace

uint64_t pixel_count(const OIIO::ImageSpec& s) {
  return mul(mul(uint64_t(std::max(0, s.width)), uint64_t(std::max(0, s.height))), uint64_t(std::max(0, s.depth)));
}

uint64_t float_bytes(const OIIO::ImageSpec& s) { return mul(pixel_count(s), mul(uint64_t(std::max(0, s.nchannels)), 4)); }

uint64_t band_bytes(const OIIO::ImageSpec& s) {
  const Band band = band_of(s);
  const uint64_t pixel = saturating::add(s.pixel_bytes(true), mul(uint64_t(std::max(0, s.nchannels)), 4));
  const uint64_t bytes = mul(mul(mul(band.rows, band.slices), uint64_t(std::max(0, s.width))), pixel);
  return s.tile_width > 0 ? saturating::add(bytes, s.tile_bytes(true)) : bytes;
}

std::string read_float_bands(OIIO::ImageInput& in, const BandSink& take) { return read_bands(in, nullptr, &take); }

std::string read_float_image(OIIO::ImageInput& in, float* pixels) { return read_bands(in, pixels, nullptr); }

}  // namespace dqskin::diff_detail
