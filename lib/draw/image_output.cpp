// Rendered images as files: PNG (8-bit sRGB) or OpenEXR (32-bit linear float), written by the image module
// (image_files.hpp) to an AtomicFile's temporary and renamed when complete.
#include "dqskin/image_output.hpp"
#include "image_files.hpp"

namespace dqskin {

bool parse_image_format(const std::string& text, ImageFormat& format) {
  if (text == "png") format = ImageFormat::kPng;
  else if (text == "exr") format = ImageFormat::kExr;
  else return false;
  return true;
}

const char* extension(ImageFormat format) { return format == ImageFormat::kPng ? "png" : "exr"; }

Committed write_image(const std::string& path, const Image& image, ImageFormat format, const CommitOptions& options) {
  AtomicFile file(path, false);
  write_image(file, image, format);
  return file.commit(options);
}

void write_image(AtomicFile& file, const Image& image, ImageFormat format) {
  image_files().write_image(file, image, format);
}

}  // namespace dqskin
