// Which lossless OpenEXR compression suits vertex-animation and bone textures: re-encodes the EXR files
// given on the command line with each compression OpenEXR offers that keeps every bit (NONE, RLE, ZIPS,
// ZIP at several zlib levels, PIZ; PXR24 for half images, where it is lossless), and prints one table per
// file, side by side: bytes, share of the raw size, encode and decode throughput (best of a few runs, MB
// of raw texels per second), and whether the texels came back bit for bit. Not a CTest test: its numbers
// only mean something on a quiet machine (docs/PERFORMANCE.md, "Texture profiles").
//
// Usage: dqskin_bench_exr FILE.exr… [--threads N] [--methods LIST]
//   N: OpenImageIO's exr_threads (OpenEXR's worker threads; default 1, one worker beside the caller)
//   LIST: compressions to try, comma-separated (default: all lossless ones)
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

struct Image {
  OIIO::ImageSpec spec;
  std::vector<unsigned char> pixels;
};

bool read(const std::string& path, Image& image) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return false;
  image.spec = in->spec();
  image.pixels.resize(image.spec.image_bytes());
  return in->read_image(0, 0, 0, image.spec.nchannels, image.spec.format, image.pixels.data());
}

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> files;
  int threads = 1;
  std::vector<std::string> only;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--threads") == 0 && i + 1 < argc) {
      threads = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--methods") == 0 && i + 1 < argc) {
      std::string list = argv[++i];
      for (size_t start = 0; start <= list.size();) {
        const size_t comma = std::min(list.find(',', start), list.size());
        only.push_back(list.substr(start, comma - start));
        start = comma + 1;
      }
    } else {
      files.push_back(argv[i]);
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: dqskin_bench_exr FILE.exr... [--threads N] [--methods LIST]\n");
    return 2;
  }
  OIIO::attribute("exr_threads", threads);
  const std::filesystem::path scratch = std::filesystem::temp_directory_path() / "dqskin_bench_exr.exr";
  for (const std::string& file : files) {
    Image image;
    if (!read(file, image)) {
      std::fprintf(stderr, "%s: cannot be read: %s\n", file.c_str(), OIIO::geterror().c_str());
      return 1;
    }
    const double raw = double(image.pixels.size());
    const bool half = image.spec.format == OIIO::TypeDesc::HALF;
    std::printf("%s: %d x %d, %d channels of %s, %.1f MB raw, OpenEXR threads %d\n", file.c_str(), image.spec.width,
                image.spec.height, image.spec.nchannels, image.spec.format.c_str(), raw / 1e6, threads);
    std::printf("| compression | bytes | of raw | encode MB/s | decode MB/s | lossless |\n|---|---|---|---|---|---|\n");
    std::vector<std::string> methods = {"none", "rle", "zips", "zip:1", "zip:4", "zip:6", "zip:9", "piz"};
    if (half) methods.push_back("pxr24");
    if (!only.empty()) methods = only;
    for (const std::string& method : methods) {
      double encode = 1e30, decode = 1e30;
      uintmax_t bytes = 0;
      bool same = true;
      for (int run = 0; run < 3; ++run) {
        OIIO::ImageSpec spec = image.spec;
        spec.attribute("compression", method);
        spec.attribute("DateTime", "");
        auto out = OIIO::ImageOutput::create("openexr");
        Clock::time_point start = Clock::now();
        if (!out || !out->open(scratch.string(), spec) ||
            !out->write_image(image.spec.format, image.pixels.data()) || !out->close()) {
          std::fprintf(stderr, "%s: %s\n", method.c_str(), out ? out->geterror().c_str() : "no EXR writer");
          return 1;
        }
        encode = std::min(encode, seconds_since(start));
        bytes = std::filesystem::file_size(scratch);
        Image back;
        start = Clock::now();
        if (!read(scratch.string(), back)) return 1;
        decode = std::min(decode, seconds_since(start));
        same = same && back.pixels == image.pixels;
      }
      std::printf("| %s | %ju | %.1f%% | %.0f | %.0f | %s |\n", method.c_str(), bytes, 100.0 * double(bytes) / raw,
                  raw / 1e6 / encode, raw / 1e6 / decode, same ? "yes" : "NO");
    }
    std::printf("\n");
  }
  std::filesystem::remove(scratch);
  return 0;
}
