#include "worst_frames_sheet.hpp"
#include "../draw/bitmap_font.hpp"
#include "../draw/heat_color.hpp"
#include "../draw/image_label.hpp"

#include "dqskin/camera.hpp"
#include "dqskin/deformer.hpp"
#include "dqskin/frame_view.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

namespace dqskin::report_detail {
namespace {

constexpr int kGap = 2;

std::string printf_text(const char* pattern, double value) {
  char text[48];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

std::vector<DeformedBatch> deform(const WorstFrames& frames, BlendMode mode) {
  DeformerOptions o;
  o.mode = mode;
  o.backend = Backend::kCpu;  // the double reference, as the measurements
  std::unique_ptr<Deformer> deformer = make_deformer(nullptr, frames.asset, frames.instances, o);
  std::vector<DeformedBatch> batches;
  deformer->run(frames.clip, frames.times, [&](const DeformedBatch& b) { batches.push_back(b); });
  return batches;
}

FrameView view_at(const std::vector<DeformedBatch>& batches, size_t frame) {
  for (const DeformedBatch& b : batches)
    if (frame >= b.first_frame && frame < b.first_frame + b.frame_count) return frame_view(b, frame - b.first_frame);
  return {};
}

}  // namespace

Image worst_frames_sheet(GpuContext& context, const WorstFrames& frames) {
  const std::vector<DeformedBatch> lbs = deform(frames, BlendMode::kLbs), dqs = deform(frames, BlendMode::kDqs);
  const size_t n = frames.times.size();
  // One camera for every cell, framed on all of them, so that the cells compare.
  Bounds box;
  for (size_t f = 0; f < n; ++f) box.add(view_at(dqs, f));
  const int size = frames.cell;
  const int scale = std::max(1, size / 256);
  const int bar_w = 8 * scale, margin = 6 * scale;
  const int text_w = font::text_width("1.23e-05 m", scale);
  const int panel = margin + bar_w + 3 * scale + text_w + 2 * margin;
  const int width = kGap + int(n) * (size + kGap) + panel;
  const int height = size + 2 * kGap;
  RendererOptions options;
  options.width = options.height = size;
  options.shade = Shade::kModeDiff;
  Image sheet{width, height, std::vector<float>(size_t(width) * size_t(height) * 4)};
  fill_rect(sheet, 0, 0, width, height, glm::vec3(options.background));
  if (box.empty()) return sheet;
  Renderer renderer(context, frames.asset, frames.instances, options);
  const Camera camera = frame_camera(box, CameraOptions{}, 1.0);

  for (size_t f = 0; f < n; ++f) {
    const FrameView l = view_at(lbs, f), d = view_at(dqs, f);
    std::vector<std::vector<float>> scalars(d.primitives.size());
    for (size_t p = 0; p < d.primitives.size(); ++p) {
      const std::span<const float> a = l.primitives[p].positions, b = d.primitives[p].positions;
      scalars[p].resize(d.primitives[p].vertices);
      for (size_t v = 0; v < scalars[p].size(); ++v) {
        const double distance = glm::distance(glm::dvec3(a[3 * v], a[3 * v + 1], a[3 * v + 2]),
                                              glm::dvec3(b[3 * v], b[3 * v + 1], b[3 * v + 2]));
        scalars[p][v] = frames.scale > 0 ? float(std::min(1.0, distance / frames.scale)) : 0.0f;
      }
    }
    const Image cell = renderer.render(d, camera, scalars);
    const int x0 = kGap + int(f) * (size + kGap);
    for (int y = 0; y < size; ++y)
      std::copy_n(cell.rgba.data() + size_t(y) * size_t(size) * 4, size_t(size) * 4,
                  sheet.rgba.data() + (size_t(y + kGap) * size_t(width) + size_t(x0)) * 4);
    draw_label(sheet, printf_text("t = %.3f s", frames.times[f]), x0 + 3 * scale, kGap + 3 * scale, scale);
  }

  // The legend: a bar from 0 (bottom) to the scale (top), labelled at 0, half and top in scene units.
  const int bar_top = 24 * scale, bar_bottom = size - 16 * scale, bar_x = width - panel + margin;
  if (bar_bottom > bar_top) {
    for (int y = bar_top; y < bar_bottom; ++y)
      fill_rect(sheet, bar_x, y + kGap, bar_w, 1, heat_color(float(bar_bottom - 1 - y) / float(std::max(1, bar_bottom - bar_top - 1))));
    const int x = bar_x + bar_w + 3 * scale, half = font::kGlyphHeight * scale / 2;
    draw_label(sheet, printf_text("%.3g m", frames.scale), x, kGap + bar_top - half, scale);
    draw_label(sheet, printf_text("%.3g m", frames.scale / 2), x, kGap + (bar_top + bar_bottom) / 2 - half, scale);
    draw_label(sheet, "0 m", x, kGap + bar_bottom - 1 - half, scale);
  }
  return sheet;
}

}  // namespace dqskin::report_detail
