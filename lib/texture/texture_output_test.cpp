#include "dqskin/error.hpp"
#include "dqskin/animation.hpp"
#include "dqskin/load.hpp"
#include "texture_output.hpp"
#include "../test_support/scratch_dir.hpp"
#include "../test_support/read_file.hpp"
#include "../test_support/test_models.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// An EXR read back through OpenImageIO, as a shader's loader would read it.
struct ExrFile {
  OIIO::ImageSpec spec;
  std::vector<float> rgba;  // width × height × 4

  const float* texel(size_t x, size_t y) const { return &rgba[(y * size_t(spec.width) + x) * 4]; }
};

ExrFile read_exr(const fs::path& path) {
  ExrFile exr;
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) {
    ADD_FAILURE() << path << ": " << OIIO::geterror();
    return exr;
  }
  exr.spec = in->spec();
  EXPECT_EQ(exr.spec.nchannels, 4);
  exr.rgba.resize(size_t(exr.spec.width) * size_t(exr.spec.height) * 4);
  EXPECT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, exr.rgba.data())) << in->geterror();
  return exr;
}

using testing_support::read_file;

json read_json(const fs::path& path) { return json::parse(read_file(path)); }

// Bitwise equality, so that -0 ≠ 0 and a NaN would be caught too.
::testing::AssertionResult same_bits(float actual, float expected) {
  if (std::bit_cast<uint32_t>(actual) == std::bit_cast<uint32_t>(expected)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << actual << " != " << expected;
}

// The header a deterministic, lossless 32-bit RGBA texture must have.
void expect_texture_header(const OIIO::ImageSpec& spec) {
  EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(spec.channelnames, (std::vector<std::string>{"R", "G", "B", "A"}));
  for (int c = 0; c < spec.nchannels; ++c) EXPECT_EQ(spec.channelformat(c), OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(spec.get_string_attribute("compression"), "zip");
  EXPECT_EQ(spec.tile_width, 0) << "scanline image";
  EXPECT_EQ(spec.get_string_attribute("DateTime"), "") << "no time stamp (the header holds an empty capDate)";
  EXPECT_EQ(spec.find_attribute("Software"), nullptr);
}

class TextureOutputTest : public testing::Test {
protected:

  size_t entries() const { return size_t(std::distance(fs::directory_iterator(dir_), fs::directory_iterator())); }

  const testing_support::ScratchDir scratch_{"texture"};
  const fs::path dir_ = scratch_.path();
};

std::vector<double> grid(size_t frames, double fps) {
  std::vector<double> t;
  for (size_t i = 0; i < frames; ++i) t.push_back(double(i) / fps);
  return t;
}

// Bone textures of every frame of a clip of `file`'s skin 0, written and read back.
struct BonesCase {
  Asset asset;
  std::vector<double> times;
  BoneTexture texture;
};

BonesCase bones_of(const std::string& path, std::vector<double> times) {
  BonesCase b;
  b.asset = load_asset(path);
  b.times = std::move(times);
  std::vector<JointTransforms> frames;
  for (double t : b.times) frames.push_back(joint_transforms(b.asset.skins[0], sample_pose(b.asset, &b.asset.clips[0], t)));
  b.texture = pack_bone_texture(frames);
  return b;
}

void expect_bone_texture(const fs::path& exr, const BoneTexture& texture) {
  const ExrFile image = read_exr(exr);
  expect_texture_header(image.spec);
  ASSERT_EQ(size_t(image.spec.width), texture.width());
  ASSERT_EQ(size_t(image.spec.height), texture.frames);
  ASSERT_EQ(image.rgba.size(), texture.rgba.size());
  for (size_t i = 0; i < image.rgba.size(); ++i) ASSERT_TRUE(same_bits(image.rgba[i], texture.rgba[i])) << "float " << i;
}

TEST_F(TextureOutputTest, BoneTextureIsTheRgbaBitForBit) {
  for (const char* rig : {"bending_arm.gltf", "nonuniform_scale.gltf"}) {
    SCOPED_TRACE(rig);
    const BonesCase b = bones_of(std::string(DQSKIN_TESTDATA_DIR) + "/" + rig, grid(7, 6));
    EXPECT_EQ(b.texture.texels_per_joint, std::string(rig) == "bending_arm.gltf" ? 2 : 5);
    const fs::path exr = dir_ / (std::string(rig) + ".bones.exr");
    const fs::path side = dir_ / (std::string(rig) + ".bones.json");
    EXPECT_EQ(write_bone_texture(exr.string(), side.string(), b.texture, b.asset, 0, b.times, 6, Overwrite::kReplace),
              (std::vector<Committed>{Committed::kWritten, Committed::kWritten}));
    expect_bone_texture(exr, b.texture);

    const json j = read_json(side);
    const Skin& skin = b.asset.skins[0];
    EXPECT_EQ(j["skin"], 0);
    EXPECT_EQ(j["skin_name"], skin.name);
    ASSERT_EQ(j["joints"].size(), skin.joints.size());
    for (size_t i = 0; i < skin.joints.size(); ++i) EXPECT_EQ(j["joints"][i], b.asset.nodes[size_t(skin.joints[i])].name);
    EXPECT_EQ(j["texels_per_joint"], b.texture.texels_per_joint);
    EXPECT_EQ(j["frame_count"], 7);
    EXPECT_EQ(j["fps"], 6.0);
    for (size_t i = 0; i < b.times.size(); ++i) EXPECT_EQ(j["frame_times"][i].get<double>(), b.times[i]);
    EXPECT_EQ(j["file"], exr.filename().string());

    // Written again: the same bytes, and under kRefuseDifferent nothing to do.
    const std::string first = read_file(exr);
    EXPECT_EQ(write_bone_texture(exr.string(), side.string(), b.texture, b.asset, 0, b.times, 6,
                                 Overwrite::kRefuseDifferent),
              (std::vector<Committed>{Committed::kUnchanged, Committed::kUnchanged}));
    EXPECT_EQ(read_file(exr), first);
  }
  EXPECT_EQ(entries(), 4u);
}

TEST_F(TextureOutputTest, BoneTextureUnwritableFolderIsAnOutputErrorNamingTheFile) {
  const BonesCase b = bones_of(std::string(DQSKIN_TESTDATA_DIR) + "/bending_arm.gltf", grid(2, 2));
  const fs::path exr = dir_ / "missing" / "bones.exr";
  try {
    write_bone_texture(exr.string(), (dir_ / "bones.json").string(), b.texture, b.asset, 0, b.times, 2,
                       Overwrite::kReplace);
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(exr.string() + ": ", 0), 0u) << e.what();
  }
  EXPECT_EQ(entries(), 0u);
}

// The shared sample models (../shared/testdata): the bone texture of skin 0 over eight frames spread over
// the first clip. (The VAT writer's round trips are lib/texture/vat_writer_test.cpp's.)
class SharedModelTextures : public TextureOutputTest, public testing::WithParamInterface<const char*> {};

TEST_P(SharedModelTextures, RoundTripOneClip) {
  const fs::path path = fs::path(DQSKIN_SHARED_TESTDATA_DIR) / GetParam();
  if (!fs::exists(path)) GTEST_SKIP() << "shared test data not found: " << path;
  const Asset probe = load_asset(path.string());
  const std::vector<double> all = frame_times(probe.clips[0], FrameSpec{});
  std::vector<double> times;
  for (size_t i = 0; i < 8; ++i) times.push_back(all[i * (all.size() - 1) / 7]);
  ASSERT_FALSE(probe.skins.empty()) << GetParam() << " has no skin";
  {
    const BonesCase b = bones_of(path.string(), times);
    write_bone_texture((dir_ / "bones.exr").string(), (dir_ / "bones.json").string(), b.texture, b.asset, 0, b.times, 0,
                       Overwrite::kReplace);
    expect_bone_texture(dir_ / "bones.exr", b.texture);
  }
}

INSTANTIATE_TEST_SUITE_P(Models, SharedModelTextures,
                         testing::Values("RiggedSimple/RiggedSimple.glb", "RiggedFigure/RiggedFigure.glb",
                                         "CesiumMan/CesiumMan.glb", "SimpleSkin/SimpleSkin.gltf", "Fox/Fox.glb",
                                         "BrainStem/BrainStem.glb", "RecursiveSkeletons/RecursiveSkeletons.glb",
                                         "raylib_robot/robot.glb", "raylib_greenman/greenman.glb"),
                         testing_support::model_test_name);

}  // namespace
}  // namespace dqskin
