// A built-in 5x7 pixel font for the labels dqskin draws into images (contact-sheet frame numbers, heat-map
// legends), so that no system font is needed and the pixels are the same on every machine (internal to
// the image writers).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

namespace dqskin::font {

constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kAdvance = 6;  // a column of space between glyphs

// One byte per row from the top, bit 4 the leftmost pixel.
using Glyph = std::array<uint8_t, kGlyphHeight>;

// The glyph of `c`: digits, ". - + = %", the letters "c e k m s t u" (units and times), "F I L P" (FLIP)
// and space; any other character is drawn as '?'.
const Glyph& glyph(char c);

// Width in pixels of `text` drawn with every font pixel a `scale` square (without the last gap).
inline int text_width(std::string_view text, int scale) {
  return text.empty() ? 0 : scale * (kAdvance * int(text.size()) - 1);
}

// Calls set(x, y) for every lit pixel of `text` drawn at (x, y) (its top-left corner) at `scale`.
template <class SetPixel>
void draw(std::string_view text, int x, int y, int scale, const SetPixel& set) {
  for (size_t i = 0; i < text.size(); ++i) {
    const Glyph& g = glyph(text[i]);
    for (int row = 0; row < kGlyphHeight; ++row)
      for (int col = 0; col < kGlyphWidth; ++col)
        if (g[size_t(row)] & (0x10 >> col))
          for (int dy = 0; dy < scale; ++dy)
            for (int dx = 0; dx < scale; ++dx) set(x + scale * (kAdvance * int(i) + col) + dx, y + scale * row + dy);
  }
}

}  // namespace dqskin::font
