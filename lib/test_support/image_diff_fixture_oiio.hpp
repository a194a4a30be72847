// The scratch folder and generated images of the image diff's tests (lib/diff: image_diff_test.cpp,
// flip_diff_test.cpp).
#pragma once

#include "scratch_dir.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

namespace dqskin {

// A scratch folder per test, removed afterwards.
class ImageDiffTest : public ::testing::Test {
protected:
  // Writes a width × height image of `channels` channels whose every value is `value`, except `changes`
  // (pixel index, channel, value). The format follows the extension.
  std::string image(const std::string& name, int width, int height, int channels, float value,
                    const std::vector<std::tuple<int, int, float>>& changes = {}) {
    const std::filesystem::path path = dir_ / name;
    std::filesystem::create_directories(path.parent_path());
    std::vector<float> pixels(size_t(width) * size_t(height) * size_t(channels), value);
    for (const auto& [pixel, channel, v] : changes) pixels[size_t(pixel) * size_t(channels) + size_t(channel)] = v;
    const bool exr = path.extension() == ".exr";
    OIIO::ImageSpec spec(width, height, channels, exr ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
    OIIO::ImageBuf buf(spec);
    EXPECT_TRUE(buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, pixels.data()));
    EXPECT_TRUE(buf.write(path.string())) << buf.geterror();
    return path.string();
  }

  std::string text_file(const std::string& name, const std::string& contents) {
    const std::filesystem::path path = dir_ / name;
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << contents;
    return path.string();
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  const testing_support::ScratchDir scratch_{"diff"};
  const std::filesystem::path dir_ = scratch_.path();
};

}  // namespace dqskin
