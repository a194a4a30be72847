// libFuzzer target for the EXR files that `dqskin diff` reads, as images and as a bake's textures: the
// input is written as a.exr and diffed against itself, and against a 4x4 EXR made at start with a heat
// map, under --max-memory 32M: the declared size is checked against it before a pixel is read, and a
// header that lies about its size must end in one line, never a crash or an allocation past the ceiling.
#include "command_line.hpp"

#include <OpenImageIO/imageio.h>

#include <memory>

using namespace dqskin::fuzz;

namespace {

// A valid 4x4 float RGBA EXR, written once with OpenImageIO as dqskin writes EXRs (zip, no time stamp).
const fs::path& reference_exr() {
  static const fs::path path = [] {
    const fs::path out = scratch() / "reference.exr";
    OIIO::ImageSpec spec(4, 4, 4, OIIO::TypeDesc::FLOAT);
    spec.attribute("compression", "zip");
    std::vector<float> pixels(4 * 4 * 4);
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = float(i % 7) / 7.0f;
    std::unique_ptr<OIIO::ImageOutput> file = OIIO::ImageOutput::create("openexr");
    if (!file || !file->open(out.string(), spec) || !file->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) ||
        !file->close())
      std::abort();
    return out;
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  keep_stderr();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fs::path exr = scratch() / "a.exr";
  write_file(exr, data, size);
  const std::vector<std::string> limits = {"--max-memory", "32M", "--fail", "0.5"};
  std::vector<std::string> itself = {"diff", exr.string(), exr.string()};
  itself.insert(itself.end(), limits.begin(), limits.end());
  expect_status("fuzz_exr", run(itself));
  std::vector<std::string> against = {"diff", reference_exr().string(), exr.string(), "-o", (scratch() / "heat").string()};
  against.insert(against.end(), limits.begin(), limits.end());
  expect_status("fuzz_exr", run(against));
  std::error_code ignored;
  fs::remove_all(scratch() / "heat", ignored);
  fs::remove(exr, ignored);
  return 0;
}
