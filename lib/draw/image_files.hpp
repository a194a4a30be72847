// What lib/draw reads and writes through OpenImageIO, done by the image module (image_files_oiio.cpp in
// libdqskin_image.so; base/image_module.hpp says why it is apart): rendered frames, contact sheets, GIFs
// and the decoding of glTF textures.
#pragma once

#include "dqskin/asset.hpp"
#include "dqskin/image_output.hpp"

#include <memory>
#include <string>

namespace dqskin {

struct GifWriter::Impl {
  virtual ~Impl() = default;
  // Appends a frame (the first fixes the size); `index` counts the frames added before it.
  virtual void add(const Image& frame, size_t index) = 0;
  // Closes and commits the file holding `frames` frames.
  virtual Committed commit(const CommitOptions& options, size_t frames) = 0;
};

class ImageFiles {
public:
  // write_image(AtomicFile&, …) of dqskin/image_output.hpp.
  virtual void write_image(AtomicFile& file, const Image& image, ImageFormat format) const = 0;
  // `frame` resized to width × height (OpenImageIO's default filter, one thread); InputError on failure.
  virtual Image resize(const Image& frame, int width, int height) const = 0;
  // An 8-bit sRGB PNG with straight alpha.
  virtual void write_png(AtomicFile& file, const Image8& image) const = 0;
  // GifWriter's file, with its contract.
  virtual std::unique_ptr<GifWriter::Impl> open_gif(std::string path, double fps) const = 0;
  // decode_texture_image of texture_image.hpp.
  virtual Image8 decode_texture_image(const EncodedImage& image, size_t index, int max_side) const = 0;

protected:
  ~ImageFiles() = default;
};

// The module's ImageFiles, loaded on first call (its entry point: dqskin_image_files).
const ImageFiles& image_files();

}  // namespace dqskin
