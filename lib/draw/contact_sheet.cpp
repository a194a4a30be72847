// Whole-animation review images: contact sheets (a grid of resized frames with their numbers drawn in a
// built-in digit font) and animated GIFs, both written atomically by the image module (image_files.hpp).
#include "dqskin/image_output.hpp"
#include "image_files.hpp"
#include "../base/srgb.hpp"
#include "bitmap_font.hpp"

#include "dqskin/error.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace dqskin {
namespace {

constexpr std::array<uint8_t, 4> kGapColor{16, 16, 16, 255};

void fill(Image8& image, int x0, int y0, int w, int h, const std::array<uint8_t, 4>& color) {
  for (int y = std::max(0, y0); y < std::min(image.height, y0 + h); ++y)
    for (int x = std::max(0, x0); x < std::min(image.width, x0 + w); ++x)
      std::copy(color.begin(), color.end(), image.rgba.data() + (size_t(y) * size_t(image.width) + size_t(x)) * 4);
}

}  // namespace

Image8 to_srgb8(const Image& image) {
  Image8 out{image.width, image.height, std::vector<uint8_t>(image.rgba.size())};
  for (size_t i = 0; i < out.rgba.size(); ++i)
    out.rgba[i] = i % 4 == 3 ? io::unorm8(image.rgba[i]) : io::srgb8(image.rgba[i]);
  return out;
}

int draw_number(Image8& image, int x, int y, int number, int scale) {
  const std::string digits = std::to_string(std::max(0, number));
  const int width = scale * (font::kAdvance * int(digits.size()) + 1), height = scale * (font::kGlyphHeight + 2);
  fill(image, x, y, width, height, {0, 0, 0, 255});
  font::draw(digits, x + scale, y + scale, scale, [&](int px, int py) { fill(image, px, py, 1, 1, {255, 255, 255, 255}); });
  return width;
}

ContactSheet::ContactSheet(int cell_width) : cell_width_(cell_width) {
  if (cell_width < 1) throw InputError("contact sheet cells must be at least 1 pixel wide");
}

void ContactSheet::add(const Image& frame, int number) {
  if (!cells_.empty() && (frame.width != frames_width_ || frame.height != frames_height_))
    throw InputError("contact sheet frames differ in size");
  frames_width_ = frame.width, frames_height_ = frame.height;
  const int height = std::max(1, int(std::lround(double(cell_width_) * frame.height / frame.width)));
  const Image resized = image_files().resize(frame, cell_width_, height);
  cells_.push_back(to_srgb8(resized));
  numbers_.push_back(number);
}

Image8 ContactSheet::compose() const {
  if (cells_.empty()) throw InputError("a contact sheet needs at least one frame");
  const int n = int(cells_.size());
  const int columns = int(std::ceil(std::sqrt(double(n)) - 1e-9)), rows = (n + columns - 1) / columns;
  const int cw = cells_[0].width, ch = cells_[0].height;
  Image8 sheet{columns * cw + (columns + 1) * kSheetGap, rows * ch + (rows + 1) * kSheetGap, {}};
  sheet.rgba.resize(size_t(sheet.width) * size_t(sheet.height) * 4);
  fill(sheet, 0, 0, sheet.width, sheet.height, kGapColor);
  const int scale = std::max(1, cw / 128);
  for (int i = 0; i < n; ++i) {
    const int x0 = kSheetGap + (i % columns) * (cw + kSheetGap), y0 = kSheetGap + (i / columns) * (ch + kSheetGap);
    const Image8& cell = cells_[size_t(i)];
    for (int y = 0; y < ch; ++y)
      std::copy_n(cell.rgba.data() + size_t(y) * size_t(cw) * 4, size_t(cw) * 4,
                  sheet.rgba.data() + (size_t(y0 + y) * size_t(sheet.width) + size_t(x0)) * 4);
    // The label stays inside its cell: clip it to the cell by drawing into a copy of the cell's area.
    Image8 label{cw, ch, std::vector<uint8_t>(cell.rgba)};
    draw_number(label, 0, 0, numbers_[size_t(i)], scale);
    for (int y = 0; y < ch; ++y)
      std::copy_n(label.rgba.data() + size_t(y) * size_t(cw) * 4, size_t(cw) * 4,
                  sheet.rgba.data() + (size_t(y0 + y) * size_t(sheet.width) + size_t(x0)) * 4);
  }
  return sheet;
}

Committed ContactSheet::write(const std::string& path, const CommitOptions& options) const {
  const Image8 sheet = compose();
  AtomicFile file(path, false);
  image_files().write_png(file, sheet);
  return file.commit(options);
}

GifWriter::GifWriter(std::string path, double fps) : impl_(image_files().open_gif(std::move(path), fps)) {}

GifWriter::~GifWriter() = default;

void GifWriter::add(const Image& frame) {
  impl_->add(frame, frames_);
  ++frames_;
}

Committed GifWriter::commit(const CommitOptions& options) { return impl_->commit(options, frames_); }

}  // namespace dqskin
