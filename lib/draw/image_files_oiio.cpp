// lib/draw's files through OpenImageIO: rendered frames (PNG, EXR), contact sheets, animated GIFs and the
// decoding of glTF textures. Part of the image module (base/image_module.hpp).
#include "image_files.hpp"
#include "../base/image_file_oiio.hpp"
#include "../base/oiio_message.hpp"
#include "../base/srgb.hpp"
#include "../base/stderr_capture.hpp"

#include "dqskin/error.hpp"
#include "dqskin/memory_ceiling.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
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

// One GifWriter's file: OpenImageIO's GIF writer, a subimage a frame.
class OiioGif final : public GifWriter::Impl {
public:
  OiioGif(std::string path, double frames_per_second)
      : file(std::move(path), false), temporary(file.hand_over()), fps(frames_per_second) {
    if (!(fps > 0)) throw InputError("a GIF needs frames per second above 0");
    out = OIIO::ImageOutput::create("gif");
    if (!out) fail();
  }

  ~OiioGif() override {
    if (out && written > 0) out->close();
  }

  void add(const Image& frame, size_t index) override {
    if (index > 0 && (frame.width != spec.width || frame.height != spec.height))
      throw InputError("GIF frames differ in size");
    if (index == 0) {
      spec = OIIO::ImageSpec(frame.width, frame.height, 3, OIIO::TypeDesc::UINT8);
      spec.attribute("oiio:ColorSpace", "sRGB");
      // GIF counts delays in hundredths of a second; a rational keeps fractional rates such as 29.97.
      // Clamped first: lround of a rate beyond long's range has no defined value.
      const int rate[2] = {int(std::lround(std::clamp(fps, 1e-3, 1e6) * 1000)), 1000};
      spec.attribute("FramesPerSecond", OIIO::TypeRational, rate);
      spec.attribute("oiio:Movie", 1);
      spec.attribute("gif:LoopCount", 0);  // loop forever
    }
    if (!out->open(temporary, spec, index == 0 ? OIIO::ImageOutput::Create : OIIO::ImageOutput::AppendSubimage))
      fail();
    // GIF has no partial transparency: color only.
    const Image8 pixels = to_srgb8(frame);
    std::vector<uint8_t> rgb(size_t(frame.width) * size_t(frame.height) * 3);
    for (size_t p = 0; p < rgb.size() / 3; ++p) std::copy_n(pixels.rgba.data() + p * 4, 3, rgb.data() + p * 3);
    if (!out->write_image(OIIO::TypeDesc::UINT8, rgb.data())) fail();
    written = index + 1;
  }

  Committed commit(const CommitOptions& options, size_t frames) override {
    if (frames == 0) throw OutputError(file.path() + ": a GIF needs at least one frame");
    if (!out->close()) fail();
    out.reset();
    return file.commit(options);
  }

private:
  [[noreturn]] void fail() const {
    throw OutputError(file.path() + ": " + oiio_message(out ? out->geterror() : OIIO::geterror()));
  }

  AtomicFile file;
  std::string temporary;
  std::unique_ptr<OIIO::ImageOutput> out;
  OIIO::ImageSpec spec;
  double fps;
  size_t written = 0;
};

class OiioImageFiles final : public ImageFiles {
public:
  void write_image(AtomicFile& file, const Image& image, ImageFormat format) const override {
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

  Image resize(const Image& frame, int width, int height) const override {
    OIIO::ImageBuf source(OIIO::ImageSpec(frame.width, frame.height, 4, OIIO::TypeDesc::FLOAT));
    source.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, frame.rgba.data());
    OIIO::ImageBuf cell(OIIO::ImageSpec(width, height, 4, OIIO::TypeDesc::FLOAT));
    // One thread, so that the result cannot depend on how the work is split.
    if (!OIIO::ImageBufAlgo::resize(cell, source, "", 0, OIIO::ROI(), 1))
      throw InputError("contact sheet: " + oiio_message(cell.geterror()));
    Image resized{width, height, std::vector<float>(size_t(width) * size_t(height) * 4)};
    cell.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, resized.rgba.data());
    return resized;
  }

  void write_png(AtomicFile& file, const Image8& image) const override {
    OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    spec.attribute("oiio:UnassociatedAlpha", 1);
    io::write_image_file(file, "png", spec, OIIO::TypeDesc::UINT8, image.rgba.data());
  }

  std::unique_ptr<GifWriter::Impl> open_gif(std::string path, double fps) const override {
    return std::make_unique<OiioGif>(std::move(path), fps);
  }

  Image8 decode_texture_image(const EncodedImage& image, size_t index, int max_side) const override {
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
};

}  // namespace
}  // namespace dqskin

// The entry point base/image_module.hpp looks up: the address of this folder's ImageFiles.
extern "C" const void* dqskin_image_files() {
  static const dqskin::OiioImageFiles files;
  return static_cast<const dqskin::ImageFiles*>(&files);
}
