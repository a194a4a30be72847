// Reading images a band of rows at a time (image_bands.hpp), and the image diff's refusal of an image whose
// declared size needs more than --max-memory.
#include "image_bands_oiio.hpp"

#include "dqskin/image_diff.hpp"
#include "../test_support/scratch_dir.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <vector>

namespace dqskin::diff_detail {
namespace {

namespace fs = std::filesystem;

class ImageBandsTest : public ::testing::Test {
protected:
  // Writes `spec`'s image (its format, per-channel formats and tiles as given) with values that differ
  // at every pixel and channel, in the file format the extension names.
  std::string write(const std::string& name, const OIIO::ImageSpec& spec) {
    const std::string path = (dir_ / name).string();
    std::vector<float> values(size_t(spec.width) * size_t(spec.height) * size_t(spec.depth) * size_t(spec.nchannels));
    for (size_t i = 0; i < values.size(); ++i) values[i] = float(i % 251) / 250.0f + float(i % 7) * 0.125f;
    OIIO::ImageBuf buf(spec);
    EXPECT_TRUE(buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, values.data()));
    EXPECT_TRUE(buf.write(path)) << buf.geterror();
    return path;
  }

  // read_float_bands of `path` equals OpenImageIO's read_image as float, value for value, and came in
  // at least `bands` bands, in order; so does read_float_image.
  void expect_as_read_image(const std::string& path, size_t bands) {
    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in) << OIIO::geterror();
    const OIIO::ImageSpec spec = in->spec();
    const size_t channels = size_t(spec.nchannels);
    std::vector<float> expected(size_t(float_bytes(spec) / 4)), got(expected.size(), NAN);
    ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, expected.data())) << in->geterror();
    size_t next = 0, seen = 0;
    const std::string why = read_float_bands(*in, [&](const float* values, size_t first, size_t pixels) {
      EXPECT_EQ(first, next);
      std::copy_n(values, pixels * channels, got.begin() + std::ptrdiff_t(first * channels));
      next = first + pixels;
      ++seen;
    });
    EXPECT_EQ(why, "");
    EXPECT_EQ(next, size_t(pixel_count(spec)));
    EXPECT_GE(seen, bands);
    EXPECT_TRUE(got == expected) << path;
    std::vector<float> whole(expected.size(), NAN);
    EXPECT_EQ(read_float_image(*in, whole.data()), "");
    EXPECT_TRUE(whole == expected) << path;
  }

  const testing_support::ScratchDir scratch_{"image_bands"};
  const fs::path dir_ = scratch_.path();
};

TEST_F(ImageBandsTest, EightBitPngIsReadAsReadImageConvertsIt) {
  expect_as_read_image(write("a.png", OIIO::ImageSpec(37, 21, 4, OIIO::TypeDesc::UINT8)), 1);
}

TEST_F(ImageBandsTest, HalfExrOfManyBandsIsReadAsReadImageConvertsIt) {
  // 4096 pixels of 4 channels a row: 64 rows a band, so 300 rows are five bands.
  expect_as_read_image(write("a.exr", OIIO::ImageSpec(4096, 300, 4, OIIO::TypeDesc::HALF)), 5);
}

TEST_F(ImageBandsTest, ExrWithChannelsOfDifferentFormatsIsReadAsReadImageConvertsIt) {
  OIIO::ImageSpec spec(19, 11, 3, OIIO::TypeDesc::HALF);
  spec.channelformats = {OIIO::TypeDesc::HALF, OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::HALF};
  expect_as_read_image(write("mixed.exr", spec), 1);
}

TEST_F(ImageBandsTest, TiledExrWithPartialTilesIsReadAsReadImageConvertsIt) {
  OIIO::ImageSpec spec(4100, 200, 4, OIIO::TypeDesc::HALF);
  spec.tile_width = spec.tile_height = 64;  // partial tiles on the right and at the bottom; 128-row bands
  expect_as_read_image(write("tiled.exr", spec), 2);
}

TEST_F(ImageBandsTest, TakesOneBandBesidesTheFloatPixels) {
  const OIIO::ImageSpec spec(12000, 12000, 4, OIIO::TypeDesc::HALF);
  EXPECT_EQ(float_bytes(spec), uint64_t(12000) * 12000 * 16);
  // 21 rows of 12000 pixels make a band of at most 2^20 values; each as half and as float.
  EXPECT_EQ(band_bytes(spec), uint64_t(21) * 12000 * (8 + 16));
  OIIO::ImageSpec huge(2000000000, 2000000000, 1000, OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(float_bytes(huge), UINT64_MAX);  // saturates, never wraps to a small size
}

TEST_F(ImageBandsTest, DiffRefusesAnImageOverMaxMemoryBeforeReadingIt) {
  const std::string a = write("a.exr", OIIO::ImageSpec(256, 256, 4, OIIO::TypeDesc::FLOAT));
  DiffOptions options;
  // Reading A takes 1 MiB of float pixels and a band, here the whole image as float and as read: 3 MiB.
  options.max_memory = 2 << 20;
  ImageDiff d = diff_pair({"a.exr", a, a, "a.exr.diff.png"}, options);
  EXPECT_EQ(d.status, DiffStatus::kFail);
  EXPECT_EQ(d.unreadable, a);
  EXPECT_EQ(d.read_error,
            "comparing it needs about 3.00 MiB (its 256x256 pixels of 4 channels as float), more than --max-memory 2.00 MiB");
  options.max_memory = 7 << 19;  // A fits; B beside it does not
  d = diff_pair({"a.exr", a, a, "a.exr.diff.png"}, options);
  EXPECT_EQ(d.read_error, "comparing it needs about 4.00 MiB (its 256x256 pixels of 4 channels as float, beside 1.00 MiB "
                          "for the other image), more than --max-memory 3.50 MiB");
  options.max_memory = 4 << 20;
  EXPECT_EQ(diff_pair({"a.exr", a, a, "a.exr.diff.png"}, options).status, DiffStatus::kPass);
}

}  // namespace
}  // namespace dqskin::diff_detail
