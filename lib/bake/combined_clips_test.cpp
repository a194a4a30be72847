// Several clips in one texture (--combine-clips, docs/DESIGN.md §4.9): the combined texture is the
// per-clip textures one after another, row for row, with a clip table that finds each clip, and each clip is
// checked on its own.
#include "dqskin/bake.hpp"

#include "dqskin/error.hpp"
#include "../test_support/read_file.hpp"
#include "../test_support/scratch_dir.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing_support::read_file;

std::string rig(const char* name) { return std::string(DQSKIN_TESTDATA_DIR) + "/" + name; }

// An image's texels as floats, every channel, rows top first.
struct Texels {
  int width = 0, height = 0, channels = 0;
  std::vector<float> values;
  // Rows [first, first + count) of the image.
  std::vector<float> rows(size_t first, size_t count) const {
    const size_t row = size_t(width) * size_t(channels);
    return {values.begin() + std::ptrdiff_t(first * row), values.begin() + std::ptrdiff_t((first + count) * row)};
  }
};

Texels read_texels(const fs::path& p) {
  Texels t;
  auto in = OIIO::ImageInput::open(p.string());
  EXPECT_TRUE(in) << p;
  if (!in) return t;
  t.width = in->spec().width;
  t.height = in->spec().height;
  t.channels = in->spec().nchannels;
  t.values.resize(size_t(t.width) * size_t(t.height) * size_t(t.channels));
  EXPECT_TRUE(in->read_image(0, 0, 0, t.channels, OIIO::TypeDesc::FLOAT, t.values.data()));
  return t;
}

class CombinedClipsTest : public testing::Test {
protected:
  BakeOptions options(const std::string& folder, unsigned formats, bool combine) {
    BakeOptions o;
    o.plan.out_dir = (root_ / folder).string();
    o.formats = formats;
    o.backend = Backend::kFastCpu;  // no GL context needed; the float deformer is deterministic
    o.jobs = 2;
    o.textures.combine_clips = combine;
    return o;
  }

  const testing_support::ScratchDir scratch_{"combined_clips"};
  const fs::path root_ = scratch_.path();
};

const unsigned kTextures = unsigned(BakeFormat::kVat) | unsigned(BakeFormat::kBones);

// The clip table of a combined side file against the per-clip bakes: rows, frames, rates, durations, and
// the same decode-back figures as each clip's own texture.
void expect_table_matches(const json& combined, const fs::path& apart, const std::string& stem,
                          const std::string& side_file, const std::vector<std::string>& clips) {
  ASSERT_EQ(combined["clips"].size(), clips.size()) << combined["clips"].dump();
  size_t first = 0;
  for (size_t c = 0; c < clips.size(); ++c) {
    SCOPED_TRACE(clips[c]);
    const json& entry = combined["clips"][c];
    const json own = json::parse(read_file(apart / stem / clips[c] / side_file));
    const json& own_entry = own["clips"][0];
    EXPECT_EQ(entry["name"], clips[c]);
    EXPECT_EQ(entry["first_frame"].get<size_t>(), first);
    EXPECT_EQ(entry["frame_count"], own_entry["frame_count"]);
    EXPECT_EQ(entry["fps"], own_entry["fps"]);
    EXPECT_EQ(entry["duration"], own_entry["duration"]);
    EXPECT_EQ(entry["loop"], own_entry["loop"]);
    // The same texels decoded against the same deformation: the same figures.
    EXPECT_EQ(entry["decode_check"], own["decode_check"]);
    first += entry["frame_count"].get<size_t>();
  }
  EXPECT_EQ(combined["frame_count"].get<size_t>(), first);
}

// Bakes `input` once per clip and once combined, and compares: every texture of the combined bake holds
// the per-clip textures' rows in clip order, bit for bit (the dqskin VAT stores absolute positions and
// bone textures joint transforms: nothing in a row depends on the other clips).
void expect_combined_equals_apart(const BakeOptions& apart_options,
                                  const BakeOptions& combined_options, const std::string& input,
                                  const std::string& stem, const std::vector<std::string>& clips) {
  SCOPED_TRACE(input);
  const BakeReport apart = bake({input}, apart_options);
  ASSERT_FALSE(apart.any_failed()) << apart.inputs[0].error;
  const BakeReport together = bake({input}, combined_options);
  ASSERT_FALSE(together.any_failed()) << together.inputs[0].error;
  const fs::path a = apart_options.plan.out_dir, b = combined_options.plan.out_dir;

  // The VAT: the positions image, row blocks per clip.
  const json vat = json::parse(read_file(b / stem / "vat.json"));
  EXPECT_TRUE(vat["clip"].is_null());
  expect_table_matches(vat, a, stem, "vat.json", clips);
  const Texels whole = read_texels(b / stem / "vat_positions.exr");
  size_t row = 0;
  for (const std::string& clip : clips) {
    const Texels own = read_texels(a / stem / clip / "vat_positions.exr");
    ASSERT_EQ(own.width, whole.width);
    EXPECT_TRUE(whole.rows(row, size_t(own.height)) == own.values) << clip << ": rows from " << row;
    row += size_t(own.height);
  }
  EXPECT_EQ(row, size_t(whole.height));

  // The bone texture: one row per frame.
  const json bones = json::parse(read_file(b / stem / "bones_skin0.json"));
  const Texels whole_bones = read_texels(b / stem / "bones_skin0.exr");
  row = 0;
  ASSERT_EQ(bones["clips"].size(), clips.size());
  for (size_t c = 0; c < clips.size(); ++c) {
    const Texels own = read_texels(a / stem / clips[c] / "bones_skin0.exr");
    EXPECT_EQ(bones["clips"][c]["first_row"].get<size_t>(), row);
    EXPECT_TRUE(whole_bones.rows(row, size_t(own.height)) == own.values) << clips[c];
    const json own_side = json::parse(read_file(a / stem / clips[c] / "bones_skin0.json"));
    EXPECT_EQ(bones["clips"][c]["decode_check"], own_side["decode_check"]) << clips[c];
    row += size_t(own.height);
  }
  EXPECT_EQ(row, size_t(whole_bones.height));

  // The report (and so the manifest) keeps one check per clip and texture, as apart.
  EXPECT_EQ(together.checks.size(), apart.checks.size());
  for (size_t i = 0; i < std::min(together.checks.size(), apart.checks.size()); ++i) {
    EXPECT_EQ(together.checks[i].clip, apart.checks[i].clip);
    EXPECT_EQ(together.checks[i].texture, apart.checks[i].texture);
    EXPECT_EQ(together.checks[i].max_error, apart.checks[i].max_error);
  }
  // Nothing was left in the clips' folders: the textures are the input's.
  for (const std::string& clip : clips) EXPECT_FALSE(fs::exists(b / stem / clip)) << clip;
}

TEST_F(CombinedClipsTest, TheCombinedTextureIsThePerClipTexturesOneAfterAnother) {
  expect_combined_equals_apart(options("apart", kTextures, false), options("together", kTextures, true),
                               rig("interpolation_modes.gltf"), "interpolation_modes", {"cubic", "step"});
}

TEST_F(CombinedClipsTest, ASharedModelsClipsCombineAsApart) {
  const fs::path fox = fs::path(DQSKIN_SHARED_TESTDATA_DIR) / "Fox" / "Fox.glb";
  if (!fs::exists(fox)) GTEST_SKIP() << "shared test data not found: " << fox;
  BakeOptions apart = options("fox_apart", kTextures, false), together = options("fox_together", kTextures, true);
  for (BakeOptions* o : {&apart, &together}) o->plan.frames.fps = 6;  // every clip, fewer frames
  expect_combined_equals_apart(apart, together, fox.string(), "Fox", {"Survey", "Walk", "Run"});
}

TEST_F(CombinedClipsTest, AFrameDecimationAppliesToEveryClip) {
  // With a budget the planner chooses one type and one decimation for the whole texture; each clip keeps
  // its own grid's frames of it (the first, every step-th, and one at or past its end) at its rate / step.
  // Float at every frame takes 209 KiB here: 120 KiB of float needs a decimation.
  BakeOptions apart = options("planned_apart", unsigned(BakeFormat::kVat), false);
  const BakeReport full = bake({rig("interpolation_modes.gltf")}, apart);
  ASSERT_FALSE(full.any_failed()) << full.inputs[0].error;
  BakeOptions o = options("planned", unsigned(BakeFormat::kVat), true);
  o.textures.max_bytes = 120 << 10;
  o.textures.encoding = "float";
  const BakeReport report = bake({rig("interpolation_modes.gltf")}, o);
  ASSERT_FALSE(report.any_failed()) << report.inputs[0].error;
  const json vat = json::parse(read_file(root_ / "planned" / "interpolation_modes" / "vat.json"));
  ASSERT_TRUE(vat.contains("plan")) << vat.dump();
  EXPECT_LE(vat["plan"]["gpu_bytes"].get<uint64_t>(), uint64_t(120) << 10);
  const size_t step = vat["plan"]["frame_step"].get<size_t>();
  EXPECT_GT(step, 1u) << "120 KiB of float holds the clips at every other frame at most";
  size_t frames = 0;
  for (const json& clip : vat["clips"]) {
    SCOPED_TRACE(clip.dump());
    const json own = json::parse(read_file(root_ / "planned_apart" / "interpolation_modes" /
                                           clip["name"].get<std::string>() / "vat.json"));
    const size_t all = own["frame_count"].get<size_t>();
    EXPECT_EQ(clip["frame_count"].get<size_t>(), (all - 1 + step - 1) / step + 1);
    EXPECT_DOUBLE_EQ(clip["fps"].get<double>(), own["fps"].get<double>() / double(step));
    EXPECT_TRUE(clip.contains("decode_check"));
    EXPECT_EQ(clip["first_frame"].get<size_t>(), frames);
    frames += clip["frame_count"].get<size_t>();
  }
  EXPECT_EQ(frames, vat["frame_count"].get<size_t>());
}

TEST_F(CombinedClipsTest, OpenVatListsEveryClipInItsAnimationList) {
  BakeOptions o = options("openvat", unsigned(BakeFormat::kVat), true);
  o.textures.vat_profile = "openvat";
  ASSERT_FALSE(bake({rig("interpolation_modes.gltf")}, o).any_failed());
  const fs::path folder = root_ / "openvat" / "interpolation_modes";
  const json remap = json::parse(read_file(folder / "interpolation_modes-remap_info.json"));
  const json vat = json::parse(read_file(folder / "vat.json"));
  ASSERT_EQ(remap["animations"].size(), 2u) << remap.dump();
  // OpenVAT counts frames from 1 over the whole texture.
  for (const json& clip : vat["clips"]) {
    const json& listed = remap["animations"][clip["name"].get<std::string>()];
    EXPECT_EQ(listed["startFrame"].get<size_t>(), clip["first_frame"].get<size_t>() + 1);
    EXPECT_EQ(listed["endFrame"].get<size_t>(), clip["first_frame"].get<size_t>() + clip["frame_count"].get<size_t>());
  }
  EXPECT_EQ(remap["os-remap"]["Frames"], vat["frame_count"]);
}

// Every file under `dir` but the manifests, relative path → bytes.
std::map<std::string, std::string> files_under(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename().string().rfind("manifest", 0) != 0)
      out[fs::relative(e.path(), dir).string()] = read_file(e.path());
  return out;
}

TEST_F(CombinedClipsTest, ShardsTogetherWriteTheWholeBakesCombinedTextureOnce) {
  const unsigned formats = kTextures | unsigned(BakeFormat::kPly);
  ASSERT_FALSE(bake({rig("interpolation_modes.gltf")}, options("whole", formats, true)).any_failed());
  size_t textures = 0;
  for (unsigned i = 0; i < 3; ++i) {
    BakeOptions o = options("sharded", formats, true);
    o.plan.shard = {i, 3};
    const BakeReport report = bake({rig("interpolation_modes.gltf")}, o);
    ASSERT_FALSE(report.any_failed()) << report.inputs[0].error;
    for (const BakeOutput& out : report.outputs) textures += out.path == "interpolation_modes/vat.json";
  }
  EXPECT_EQ(textures, 1u) << "one shard writes the combined texture";
  EXPECT_TRUE(files_under(root_ / "whole") == files_under(root_ / "sharded"));
}

TEST_F(CombinedClipsTest, ProfilesWhoseRuntimesPlayOneClipPerTextureAreRefused) {
  BakeOptions houdini = options("houdini", unsigned(BakeFormat::kVat), true);
  houdini.textures.vat_profile = "houdini";
  EXPECT_THROW(bake({rig("interpolation_modes.gltf")}, houdini), InputError);
  BakeOptions cocos = options("cocos", unsigned(BakeFormat::kBones), true);
  cocos.textures.bones_profile = "dq-cocos";
  EXPECT_THROW(bake({rig("interpolation_modes.gltf")}, cocos), InputError);
  BakeOptions meshes = options("meshes", unsigned(BakeFormat::kPly), true);
  EXPECT_THROW(bake({rig("interpolation_modes.gltf")}, meshes), InputError);
  EXPECT_FALSE(fs::exists(root_ / "houdini" / "interpolation_modes"));
}

TEST_F(CombinedClipsTest, ClipsTooManyForTheSizeLimitFailTheInputAndWriteNothing) {
  // One row per frame: the bone texture of both clips is taller than 8 texels, each clip's may not be.
  BakeOptions o = options("small", unsigned(BakeFormat::kBones), true);
  o.textures.max_size = 8;
  const BakeReport report = bake({rig("interpolation_modes.gltf")}, o);
  ASSERT_TRUE(report.any_failed());
  EXPECT_NE(report.inputs[0].error.find("clips cubic, step"), std::string::npos) << report.inputs[0].error;
  EXPECT_FALSE(fs::exists(root_ / "small" / "interpolation_modes" / "bones_skin0.exr"));
}

}  // namespace
}  // namespace dqskin
