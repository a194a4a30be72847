#include "texture_image.hpp"
#include "../io/oiio_message.hpp"

#include "dqskin/error.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstring>

namespace dqskin {
namespace {

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
  OIIO::ImageSpec spec;
  if (!in->set_ioproxy(&reader) || !in->open(std::string("texture.") + format, spec, config))
    throw InputError(what + ": cannot be decoded (" + oiio_message(in->geterror()) + ")");
  if (spec.width < 1 || spec.height < 1 || spec.width > max_side || spec.height > max_side)
    throw InputError(what + ": is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                     " pixels; this GPU takes textures of 1 to " + std::to_string(max_side) + " a side");
  if (spec.nchannels < 1 || spec.nchannels > 4)
    throw InputError(what + ": has " + std::to_string(spec.nchannels) + " channels, not 1 to 4");
  const size_t pixels = size_t(spec.width) * size_t(spec.height);
  const size_t channels = size_t(spec.nchannels);
  std::vector<uint8_t> stored(pixels * channels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, stored.data()))
    throw InputError(what + ": cannot be decoded (" + oiio_message(in->geterror()) + ")");

  Image8 out;
  out.width = spec.width;
  out.height = spec.height;
  out.rgba.resize(pixels * 4);
  for (size_t p = 0; p < pixels; ++p) {
    const uint8_t* s = &stored[p * channels];
    uint8_t* d = &out.rgba[p * 4];
    // 1: grey; 2: grey and alpha; 3: RGB; 4: RGBA (PNG's colour types after expansion).
    d[0] = s[0];
    d[1] = channels >= 3 ? s[1] : s[0];
    d[2] = channels >= 3 ? s[2] : s[0];
    d[3] = channels == 2 ? s[1] : channels == 4 ? s[3] : 255;
  }
  return out;
}

}  // namespace dqskin
