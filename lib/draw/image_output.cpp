// Rendered images as files through OpenImageIO: PNG (8-bit sRGB) or OpenEXR (32-bit linear float), written
// to an AtomicFile's temporary and renamed when complete.
#include "dqskin/image_output.hpp"
#include "../base/image_file.hpp"
#include "../base/srgb.hpp"

#include "dqskin/error.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

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
  const bool png = format == ImageFormat::kPng;
  OIIO::ImageSpec spec(image.width, image.height, 4, png ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
  if (png) {
    spec.attribute("oiio:ColorSpace", "sRGB");
    // Our colors are not multiplied by alpha, as PNG stores them; without this OpenImageIO would divide
    // them by alpha on the way out.
    spec.attribute("oiio:UnassociatedAlpha", 1);
  } else {
    spec.attribute("oiio:ColorSpace", "Linear");
    spec.attribute("compression", "zip");  // lossless
    spec.attribute("DateTime", "");        // else OpenImageIO stamps the current time (capDate)
  }
  if (png) {
    std::vector<uint8_t> bytes(image.rgba.size());
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = i % 4 == 3 ? io::unorm8(image.rgba[i]) : io::srgb8(image.rgba[i]);
    io::write_image_file(file, "png", spec, OIIO::TypeDesc::UINT8, bytes.data());
  } else {
    io::write_image_file(file, "openexr", spec, OIIO::TypeDesc::FLOAT, image.rgba.data());
  }
}

}  // namespace dqskin
