// Whole-animation review images: contact sheets (a grid of resized frames with their numbers drawn in a
// built-in digit font) and animated GIFs, both through OpenImageIO and written atomically.
#include "dqskin/image_output.hpp"
#include "../base/oiio_message.hpp"
#include "../base/image_file.hpp"
#include "../base/srgb.hpp"
#include "bitmap_font.hpp"

#include "dqskin/error.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

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
  OIIO::ImageBuf source(OIIO::ImageSpec(frame.width, frame.height, 4, OIIO::TypeDesc::FLOAT));
  source.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, frame.rgba.data());
  OIIO::ImageBuf cell(OIIO::ImageSpec(cell_width_, height, 4, OIIO::TypeDesc::FLOAT));
  // One thread, so that the result cannot depend on how the work is split.
  if (!OIIO::ImageBufAlgo::resize(cell, source, "", 0, OIIO::ROI(), 1))
    throw InputError("contact sheet: " + oiio_message(cell.geterror()));
  Image resized{cell_width_, height, std::vector<float>(size_t(cell_width_) * size_t(height) * 4)};
  cell.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, resized.rgba.data());
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
  OIIO::ImageSpec spec(sheet.width, sheet.height, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  spec.attribute("oiio:UnassociatedAlpha", 1);
  io::write_image_file(file, "png", spec, OIIO::TypeDesc::UINT8, sheet.rgba.data());
  return file.commit(options);
}

struct GifWriter::Impl {
  AtomicFile file;
  std::string temporary;
  std::unique_ptr<OIIO::ImageOutput> out;
  OIIO::ImageSpec spec;
  double fps;
  Impl(std::string path, double f) : file(std::move(path), false), temporary(file.hand_over()), fps(f) {}
  [[noreturn]] void fail() const {
    throw OutputError(file.path() + ": " + oiio_message(out ? out->geterror() : OIIO::geterror()));
  }
};

GifWriter::GifWriter(std::string path, double fps) : impl_(std::make_unique<Impl>(std::move(path), fps)) {
  if (!(fps > 0)) throw InputError("a GIF needs frames per second above 0");
  impl_->out = OIIO::ImageOutput::create("gif");
  if (!impl_->out) impl_->fail();
}

GifWriter::~GifWriter() {
  if (impl_ && impl_->out && frames_ > 0) impl_->out->close();
}

void GifWriter::add(const Image& frame) {
  Impl& g = *impl_;
  if (frames_ > 0 && (frame.width != g.spec.width || frame.height != g.spec.height))
    throw InputError("GIF frames differ in size");
  if (frames_ == 0) {
    g.spec = OIIO::ImageSpec(frame.width, frame.height, 3, OIIO::TypeDesc::UINT8);
    g.spec.attribute("oiio:ColorSpace", "sRGB");
    // GIF counts delays in hundredths of a second; a rational keeps fractional rates such as 29.97.
    // Clamped first: lround of a rate beyond long's range has no defined value.
    const int rate[2] = {int(std::lround(std::clamp(g.fps, 1e-3, 1e6) * 1000)), 1000};
    g.spec.attribute("FramesPerSecond", OIIO::TypeRational, rate);
    g.spec.attribute("oiio:Movie", 1);
    g.spec.attribute("gif:LoopCount", 0);  // loop forever
  }
  if (!g.out->open(g.temporary, g.spec, frames_ == 0 ? OIIO::ImageOutput::Create : OIIO::ImageOutput::AppendSubimage))
    g.fail();
  // GIF has no partial transparency: color only.
  const Image8 pixels = to_srgb8(frame);
  std::vector<uint8_t> rgb(size_t(frame.width) * size_t(frame.height) * 3);
  for (size_t p = 0; p < rgb.size() / 3; ++p) std::copy_n(pixels.rgba.data() + p * 4, 3, rgb.data() + p * 3);
  if (!g.out->write_image(OIIO::TypeDesc::UINT8, rgb.data())) g.fail();
  ++frames_;
}

Committed GifWriter::commit(const CommitOptions& options) {
  Impl& g = *impl_;
  if (frames_ == 0) throw OutputError(g.file.path() + ": a GIF needs at least one frame");
  if (!g.out->close()) g.fail();
  g.out.reset();
  return g.file.commit(options);
}

}  // namespace dqskin
