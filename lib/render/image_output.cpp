// Rendered images as files through OpenImageIO: PNG (8-bit sRGB) or OpenEXR (32-bit linear float), written
// to an AtomicFile's temporary and renamed when complete.
#include "dqskin/render.hpp"
#include "../io/oiio_message.hpp"
#include "../io/stderr_capture.hpp"

#include "dqskin/error.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace dqskin {
namespace {

// IEC 61966-2-1 transfer function, linear [0, 1] to an 8-bit code, rounded to nearest. Done here, not by
// an sRGB framebuffer, so that the PNG bytes do not depend on the driver's conversion.
uint8_t srgb8(float linear) {
  const double c = std::clamp(double(linear), 0.0, 1.0);
  const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return uint8_t(std::lround(s * 255.0));
}

uint8_t unorm8(float value) { return uint8_t(std::lround(std::clamp(double(value), 0.0, 1.0) * 255.0)); }

}  // namespace

bool parse_image_format(const std::string& text, ImageFormat& format) {
  if (text == "png") format = ImageFormat::kPng;
  else if (text == "exr") format = ImageFormat::kExr;
  else return false;
  return true;
}

const char* extension(ImageFormat format) { return format == ImageFormat::kPng ? "png" : "exr"; }

Committed write_image(const std::string& path, const Image& image, ImageFormat format, const CommitOptions& options) {
  AtomicFile file(path, false);
  const std::string& temporary = file.hand_over();
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
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(png ? "png" : "openexr");
  if (!out) throw OutputError(path + ": " + oiio_message(OIIO::geterror()));
  CapturedStderr capture;  // libpng prints "libpng error: Write Error" (a full disk) itself; it joins our line
  auto fail = [&]() {
    const std::string library = capture.finish();
    throw OutputError(with_library_text(path + ": " + oiio_message(out->geterror()), library));
  };
  if (!out->open(temporary, spec)) fail();
  bool ok = false;
  if (png) {
    std::vector<uint8_t> bytes(image.rgba.size());
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = i % 4 == 3 ? unorm8(image.rgba[i]) : srgb8(image.rgba[i]);
    ok = out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
  } else {
    ok = out->write_image(OIIO::TypeDesc::FLOAT, image.rgba.data());
  }
  if (!ok) fail();
  if (!out->close()) fail();
  out.reset();
  capture.finish();
  return file.commit(options);
}

}  // namespace dqskin
