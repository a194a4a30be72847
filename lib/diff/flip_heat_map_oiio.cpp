// The FLIP heat map's colours through OpenImageIO's magma colormap; part of the image module.
#include "flip_heat_map.hpp"
#include "../base/image_file_oiio.hpp"
#include "../base/oiio_message.hpp"
#include "../base/saturating.hpp"
#include "../base/srgb.hpp"
#include "../draw/bitmap_font.hpp"
#include "../draw/image_label.hpp"

#include "dqskin/atomic_file.hpp"
#include "dqskin/error.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <filesystem>
#include <system_error>

namespace dqskin::diff_detail {
namespace {

namespace fs = std::filesystem;

constexpr int kMinHeight = 112;  // glyph pixels: the title, three labels and a bar between them
const glm::vec3 kPanel(0.02f);   // the panel's and the margin's dark grey (linear)

// magma's linear colours of `levels` (0 to 1), one per value.
std::vector<float> magma(const std::vector<float>& levels, const std::string& path) {
  std::vector<float> colors(levels.size() * 3);
  if (levels.empty()) return colors;
  const int n = int(levels.size());
  OIIO::ImageBuf src(OIIO::ImageSpec(n, 1, 1, OIIO::TypeDesc::FLOAT), const_cast<float*>(levels.data()));
  OIIO::ImageBuf dst(OIIO::ImageSpec(n, 1, 3, OIIO::TypeDesc::FLOAT), colors.data());
  if (!OIIO::ImageBufAlgo::color_map(dst, src, 0, "magma", {}, 1))
    throw OutputError(path + ": OpenImageIO color_map: " + oiio_message(dst.geterror()));
  return colors;
}

}  // namespace

FlipHeatMapSize flip_heat_map_size(size_t width, size_t height) {
  FlipHeatMapSize s;
  s.scale = std::max(1, int(std::min<size_t>(height, 8192) / 256));
  const int panel = 6 * s.scale + 10 * s.scale + 3 * s.scale + font::text_width("0.5", s.scale) + 6 * s.scale;
  s.width = int(width) + panel;
  s.height = std::max(int(height), kMinHeight * s.scale);
  return s;
}

uint64_t flip_heat_map_bytes(size_t width, size_t height) {
  const FlipHeatMapSize s = flip_heat_map_size(width, height);
  // Levels and colours of the map (4 + 12 bytes a pixel), the picture as float RGBA (16) and as 8-bit RGB (3).
  return saturating::add(saturating::mul(uint64_t(width) * height, 16),
                         saturating::mul(uint64_t(s.width) * uint64_t(s.height), 16 + 3));
}

void write_flip_heat_map(const std::string& path, const std::vector<double>& errors, size_t width, size_t height) {
  const FlipHeatMapSize size = flip_heat_map_size(width, height);
  Image image{size.width, size.height, std::vector<float>(size_t(size.width) * size_t(size.height) * 4)};
  fill_rect(image, 0, 0, size.width, size.height, kPanel);
  {
    std::vector<float> levels(errors.size());
    std::transform(errors.begin(), errors.end(), levels.begin(), [](double e) { return float(std::clamp(e, 0.0, 1.0)); });
    const std::vector<float> colors = magma(levels, path);
    for (size_t y = 0; y < height; ++y)
      for (size_t x = 0; x < width; ++x) {
        float* p = &image.rgba[(y * size_t(size.width) + x) * 4];
        std::copy_n(&colors[(y * width + x) * 3], 3, p);
        p[3] = 1;
      }
  }

  // The legend: "FLIP" above a bar from 1 (top) to 0 (bottom), labelled at 1, 0.5 and 0.
  const int s = size.scale, half = font::kGlyphHeight * s / 2;
  const int bar_x = int(width) + 6 * s, bar_w = 10 * s, bar_top = 18 * s, bar_bottom = size.height - 10 * s;
  draw_label(image, "FLIP", int(width) + 4 * s, 4 * s, s);
  std::vector<float> ramp(size_t(bar_bottom - bar_top));
  for (size_t i = 0; i < ramp.size(); ++i) ramp[i] = float(ramp.size() - 1 - i) / float(std::max<size_t>(ramp.size() - 1, 1));
  const std::vector<float> bar = magma(ramp, path);
  for (size_t i = 0; i < ramp.size(); ++i)
    fill_rect(image, bar_x, bar_top + int(i), bar_w, 1, glm::vec3(bar[3 * i], bar[3 * i + 1], bar[3 * i + 2]));
  const int label_x = bar_x + bar_w + 3 * s;
  draw_label(image, "1", label_x, bar_top - half, s);
  draw_label(image, "0.5", label_x, (bar_top + bar_bottom) / 2 - half, s);
  draw_label(image, "0", label_x, bar_bottom - 1 - half, s);

  std::vector<uint8_t> rgb(size_t(size.width) * size_t(size.height) * 3);
  for (size_t i = 0; i < rgb.size() / 3; ++i)
    for (size_t c = 0; c < 3; ++c) rgb[3 * i + c] = io::srgb8(image.rgba[4 * i + c]);  // OpenImageIO's colormaps are linear

  std::error_code error;
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty()) fs::create_directories(parent, error);
  if (error) throw OutputError(parent.string() + ": cannot create folder: " + error.message());
  AtomicFile file(path);
  OIIO::ImageSpec spec(size.width, size.height, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  // The only text in the file; no time stamp, so the same inputs give the same bytes.
  spec.attribute("ImageDescription", "dqskin diff heat map: FLIP per pixel, magma from 0 (black) to 1 (light yellow); "
                                     "the map is the top-left " + std::to_string(width) + "x" + std::to_string(height) +
                                     " pixels, the legend to its right");
  io::write_image_file(file, "png", spec, OIIO::TypeDesc::UINT8, rgb.data());
  file.commit(Overwrite::kReplace);
}

}  // namespace dqskin::diff_detail
