// The image files of `dqskin render`: frames as PNG (8-bit sRGB) or EXR (linear float), contact sheets and
// animated GIFs, each written atomically. They take the renderer's Images, not its context, so that
// writing and encoding need no GPU; OpenImageIO does the work in lib/render, and no OpenImageIO type
// appears here.
#pragma once

#include "dqskin/atomic_file.hpp"
#include "dqskin/renderer.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace dqskin {

enum class ImageFormat { kPng, kExr };
bool parse_image_format(const std::string& text, ImageFormat& format);
const char* extension(ImageFormat format);

// Writes `image` atomically: PNG as 8-bit sRGB (RGBA, converted from linear here, rounded to nearest),
// EXR as 32-bit linear float, no time stamp in either. Throws OutputError naming `path`.
Committed write_image(const std::string& path, const Image& image, ImageFormat format,
                      const CommitOptions& options = {});
// The same bytes into `file`'s temporary, not committed: for a writer whose files appear together.
void write_image(AtomicFile& file, const Image& image, ImageFormat format);

// 8-bit sRGB RGBA pixels, top row first: what PNG and GIF store, and what a contact sheet keeps per frame.
struct Image8 {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

// `image` encoded as write_image encodes PNGs (sRGB color, linear alpha, rounded to nearest).
Image8 to_srgb8(const Image& image);

// Contact sheets (--sheet): one PNG with every frame of a clip as a cell of a near-square grid
// (columns = ceil(sqrt(n)), rows as needed, frames left to right then top to bottom), each cell the frame
// resized (OpenImageIO's resize, single-threaded, in linear light) to `cell_width` pixels wide with its
// aspect kept, its frame number drawn in its top-left corner in a built-in 5x7 digit font (white on
// black, no system fonts), and a gap of kSheetGap dark pixels around and between the cells. Only the
// cells are kept while a clip renders, not the full frames.
constexpr int kSheetGap = 2;
class ContactSheet {
public:
  explicit ContactSheet(int cell_width = 256);
  void add(const Image& frame, int number);  // resizes the frame now
  size_t size() const { return cells_.size(); }
  Image8 compose() const;  // throws InputError when empty
  // compose() written atomically as an 8-bit sRGB PNG. Throws OutputError naming `path`.
  Committed write(const std::string& path, const CommitOptions& options = {}) const;

private:
  int cell_width_;
  int frames_width_ = 0, frames_height_ = 0;
  std::vector<Image8> cells_;
  std::vector<int> numbers_;
};

// Draws `number` (decimal digits) at (x, y) in the built-in 5x7 font, every font pixel a `scale` square,
// on a black box with a one-font-pixel margin; clipped to the image. Returns the box's width.
int draw_number(Image8& image, int x, int y, int number, int scale);

// Animated GIFs (--gif): frames appended as they arrive (OpenImageIO's GIF writer, 256-color palette per
// frame, looping), so that no frame is kept; written to a temporary and renamed by commit(). `fps` sets
// the frame delay (GIF counts it in hundredths of a second). Throws OutputError naming `path`.
class GifWriter {
public:
  GifWriter(std::string path, double fps);
  ~GifWriter();
  GifWriter(const GifWriter&) = delete;
  GifWriter& operator=(const GifWriter&) = delete;
  void add(const Image& frame);  // every frame the size of the first
  size_t frames() const { return frames_; }
  Committed commit(const CommitOptions& options = {});

  // The image module's side of the file (draw/image_files.hpp).
  struct Impl;

private:
  std::unique_ptr<Impl> impl_;
  size_t frames_ = 0;
};

}  // namespace dqskin
