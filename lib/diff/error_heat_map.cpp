#include "error_heat_map.hpp"
#include "diff_numbers.hpp"
#include "../draw/bitmap_font.hpp"
#include "../draw/heat_color.hpp"
#include "../draw/image_label.hpp"

#include "dqskin/camera.hpp"
#include "dqskin/image_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace dqskin::diff_detail {

Image render_error_heat_map(GpuContext& context, const ErrorHeatMap& map, int size) {
  const DiffSide& side = map.side;
  FrameView view;
  std::vector<std::vector<float>> scalars;
  for (size_t p = 0; p < side.first_vertex.size(); ++p) {
    const size_t first = side.first_vertex[p], n = side.primitive_size[p];
    PrimitiveView pv;
    pv.vertices = n;
    pv.positions = std::span<const float>(map.frame.positions).subspan(3 * first, 3 * n);
    if (side.file_normals[p]) pv.normals = std::span<const float>(map.frame.normals).subspan(3 * first, 3 * n);
    view.primitives.push_back(pv);
    std::vector<float>& s = scalars.emplace_back(n);
    for (size_t v = 0; v < n; ++v) s[v] = map.top > 0 ? float(std::min(1.0, double(map.error[first + v]) / map.top)) : 0.0f;
  }
  RendererOptions options;
  options.width = options.height = size;
  options.shade = Shade::kModeDiff;
  Renderer renderer(context, side.asset, side.instances, options);
  Bounds box = map.framing;
  if (box.empty()) box.add(view);
  const Image frame = renderer.render(view, frame_camera(box, CameraOptions{}, 1.0), scalars);

  // The legend in a panel of its own on the right, so that it never hides the surface: a bar from 0
  // (bottom) to top, labels at 0, half and top, in the unit the top suits.
  const int scale = std::max(1, size / 256);
  const int bar_w = 8 * scale, margin = 6 * scale;
  // The panel is as wide as the longest label length_with_unit can give ("1.23e-05 um"), not this map's:
  // every heat map of one size has one width, which the contact sheet of several clips needs.
  const int text_w = font::text_width("1.23e-05 um", scale);
  const int panel = margin + bar_w + 3 * scale + text_w + 2 * margin;
  Image image{size + panel, size, std::vector<float>(size_t(size + panel) * size_t(size) * 4)};
  for (int y = 0; y < size; ++y) {
    std::copy_n(frame.rgba.data() + size_t(y) * size_t(size) * 4, size_t(size) * 4,
                image.rgba.data() + size_t(y) * size_t(image.width) * 4);
    fill_rect(image, size, y, panel, 1, glm::vec3(options.background));
  }
  const int bar_top = 24 * scale, bar_bottom = size - 16 * scale, bar_x = size + margin;
  if (bar_bottom > bar_top) {
    for (int y = bar_top; y < bar_bottom; ++y)
      fill_rect(image, bar_x, y, bar_w, 1, heat_color(float(bar_bottom - 1 - y) / float(std::max(1, bar_bottom - bar_top - 1))));
    const int x = bar_x + bar_w + 3 * scale, half = font::kGlyphHeight * scale / 2;
    draw_label(image, length_with_unit(map.top, map.top), x, bar_top - half, scale);
    draw_label(image, length_with_unit(map.top / 2, map.top), x, (bar_top + bar_bottom) / 2 - half, scale);
    draw_label(image, length_with_unit(0, map.top), x, bar_bottom - 1 - half, scale);
  }
  draw_label(image, map.caption, 3 * scale, 3 * scale, scale);
  return image;
}

std::string heat_map_file_name(const std::string& clip) {
  std::string name = clip.empty() ? "clip" : clip;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
  return name + ".error.png";
}

void write_heat_map(const std::string& path, const Image& image) {
  write_image(path, image, ImageFormat::kPng, {Overwrite::kReplace});
}

}  // namespace dqskin::diff_detail
