#include "image_label.hpp"

#include "bitmap_font.hpp"

#include <algorithm>

namespace dqskin {

void fill_rect(Image& image, int x0, int y0, int w, int h, const glm::vec3& color) {
  for (int y = std::max(0, y0); y < std::min(image.height, y0 + h); ++y)
    for (int x = std::max(0, x0); x < std::min(image.width, x0 + w); ++x) {
      float* p = image.rgba.data() + (size_t(y) * size_t(image.width) + size_t(x)) * 4;
      p[0] = color.r, p[1] = color.g, p[2] = color.b, p[3] = 1.0f;
    }
}

void draw_label(Image& image, const std::string& text, int x, int y, int scale) {
  fill_rect(image, x - scale, y - scale, font::text_width(text, scale) + 2 * scale, (font::kGlyphHeight + 2) * scale,
            glm::vec3(0));
  font::draw(text, x, y, scale, [&](int px, int py) { fill_rect(image, px, py, 1, 1, glm::vec3(1)); });
}

}  // namespace dqskin
