#include "texture_image.hpp"
#include "../base/oiio_message.hpp"
#include "../base/stderr_capture.hpp"

#include "dqskin/error.hpp"
#include "dqskin/memory_ceiling.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstring>

namespace dqskin {
namespace {

// The most texels one image may have: 8192² (256 MiB as RGBA, before mipmaps).
constexpr size_t kMaxTexturePixels = size_t(8192) * 8192;

// The decoder is chosen by the bytes, not by the mime type or the URI's extension, which files get wrong.
// Returns the file name extension that selects OpenImageIO's reader, or null.
const char* sniff(std::span<const uint8_t> b) {
  auto starts = [&](const char* magic, size_t size, size_t at = 0) {
    return b.size() >= at + size && std::memcmp(b.data() + at, magic, size) == 0;
  };
  if (starts("\x89PNG\r\n\x1a\n", 8)) return "png";
  if (starts("\xff\xd8\xff", 3)) return "jpg";
  if (starts("RIFF", 4) && starts("WEBP", 4, 8)) return "webp";
  return nullptr;
}

}  // namespace

Image8 decode_texture_image(const EncodedImage& image, size_t index, int max_side) {
  std::string what = "image " + std::to_string(index);
  if (!image.name.empty()) what += " '" + image.name + "'";
  if (!image.uri.empty()) what += " (" + image.uri + ")";
  if (image.bytes.empty()) throw InputError(what + ": has no data (a missing or empty file?)");
  const char* format = sniff(image.bytes);
  if (!format) throw InputError(what + ": is neither PNG nor JPEG");

  OIIO::Filesystem::IOMemReader reader(image.bytes.data(), image.bytes.size());
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // glTF alpha is straight; OpenImageIO would premultiply
  // ImageInput::open(name, config, proxy) drops the proxy when given a config (OpenImageIO 2.4), so the
  // reader is made by format name and given the proxy itself.
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::create(format);
  if (!in) throw InputError(what + ": OpenImageIO has no " + format + " reader (" + oiio_message(OIIO::geterror()) + ")");
  // libpng prints its own "libpng error: …" line; it becomes part of ours.
  auto fail = [&](CapturedStderr& capture) {
    const std::string library = capture.finish();
    throw InputError(with_library_text(what + ": cannot be decoded (" + oiio_message(in->geterror()) + ")", library));
  };
  OIIO::ImageSpec spec;
  {
    CapturedStderr capture;
    if (!in->set_ioproxy(&reader) || !in->open(std::string("texture.") + format, spec, config)) fail(capture);
  }
  if (spec.width < 1 || spec.height < 1 || spec.width > max_side || spec.height > max_side)
    throw InputError(what + ": is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                     " pixels; this GPU takes textures of 1 to " + std::to_string(max_side) + " a side");
  // The header's size is checked before anything is allocated: a few bytes can claim gigapixels.
  const size_t pixels = size_t(spec.width) * size_t(spec.height);
  if (pixels > kMaxTexturePixels)
    throw InputError(what + ": is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                     " pixels, more than dqskin draws (" + std::to_string(kMaxTexturePixels) + ")");
  if (spec.nchannels < 1 || spec.nchannels > 4)
    throw InputError(what + ": has " + std::to_string(spec.nchannels) + " channels, not 1 to 4");

  Image8 out;
  out.width = spec.width;
  out.height = spec.height;
  try {
    out.rgba.resize(pixels * 4);
  } catch (const std::bad_alloc&) {
    throw InputError(what + ": " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " pixels: " +
                     out_of_memory_message());
  }
  // Read straight into RGBA (4-byte pixel stride), then fill what the stored channels lack.
  const size_t channels = size_t(spec.nchannels);
  {
    CapturedStderr capture;
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, out.rgba.data(), 4)) fail(capture);
  }
  for (size_t p = 0; p < pixels && channels < 4; ++p) {
    uint8_t* d = &out.rgba[p * 4];
    // 1: grey; 2: grey and alpha; 3: RGB (PNG's colour types after expansion).
    if (channels == 2) d[3] = d[1];
    if (channels <= 2) d[1] = d[2] = d[0];
    if (channels != 2) d[3] = 255;
  }
  return out;
}

}  // namespace dqskin
