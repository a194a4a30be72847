// Boxes and text drawn into a float image (internal to the image writers): the captions and legend numbers
// of the geometric diff's heat maps and of the report's contact sheets, in the built-in font
// (bitmap_font.hpp), so that both read the same.
#pragma once

#include "dqskin/renderer.hpp"

#include <glm/glm.hpp>

#include <string>

namespace dqskin {

// Fills the part of the rectangle (x0, y0, w, h) that lies inside the image with an opaque colour.
void fill_rect(Image& image, int x0, int y0, int w, int h, const glm::vec3& color);

// White text on a black box with a one-font-pixel margin, its top-left corner at (x, y), every font pixel a
// `scale` square.
void draw_label(Image& image, const std::string& text, int x, int y, int scale);

}  // namespace dqskin
