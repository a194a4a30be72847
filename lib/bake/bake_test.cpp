// The bake end to end through the library: every rig and shared model in every format, outputs read
// back against the deformer, manifests against the files, determinism, shards, overwrite rules.
#include "dqskin/bake.hpp"

#include "dqskin/error.hpp"
#include "dqskin/deformer.hpp"
#include "dqskin/gpu_deform.hpp"
#include "dqskin/load.hpp"
#include "dqskin/verify.hpp"
#include "../base/sha256.hpp"
#include "../test_support/ply_test_reader.hpp"
#include "../test_support/scratch_dir.hpp"
#include "../test_support/read_file.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>

namespace dqskin {
namespace {

namespace fs = std::filesystem;

const unsigned kAllFormats = 31;

std::string rig(const char* name) { return std::string(DQSKIN_TESTDATA_DIR) + "/" + name; }

// The shared models (../shared/testdata/*/*.glb|gltf, one file per folder and glTF/ variants).
std::vector<std::string> shared_models() {
  std::vector<std::string> out;
  const fs::path root = DQSKIN_SHARED_TESTDATA_DIR;
  if (!fs::is_directory(root)) return out;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.is_regular_file() && (e.path().extension() == ".glb" || e.path().extension() == ".gltf"))
      out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

class BakeTest : public testing::Test {
protected:

  BakeOptions options(const std::string& folder, unsigned formats = kAllFormats) {
    BakeOptions o;
    o.plan.out_dir = (root_ / folder).string();
    o.formats = formats;
    o.jobs = 2;
    return o;
  }

  const testing_support::ScratchDir scratch_{"bake"};
  const fs::path root_ = scratch_.path();
};

using testing_support::read_file;

// Every file under `dir`, relative path → bytes (manifests left out when asked).
std::map<std::string, std::string> tree(const fs::path& dir, bool manifests) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const std::string rel = fs::relative(e.path(), dir).string();
    if (!manifests && rel.rfind("manifest", 0) == 0) continue;
    out[rel] = read_file(e.path());
  }
  return out;
}

std::vector<float> read_exr(const fs::path& p, int& width, int& height) {
  auto in = OIIO::ImageInput::open(p.string());
  EXPECT_TRUE(in) << p;
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  width = spec.width;
  height = spec.height;
  EXPECT_EQ(spec.nchannels, 4);
  EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
  std::vector<float> pixels(size_t(width) * size_t(height) * 4);
  EXPECT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, pixels.data()));
  return pixels;
}

// Frames per second that keeps a model's longest clip to about 16 frames (the shared models' clips run
// from 0.2 s to 35 s; all formats of every frame are read back).
double modest_fps(const Asset& asset) {
  double longest = 0;
  for (const Clip& c : asset.clips) longest = std::max(longest, c.last_key);
  return longest > 0 ? std::min(8.0, 16.0 / longest) : 8.0;
}

// Bakes one file in every format on the GPU and checks every output against an independent run of the
// deformer and the manifest against the files.
void check_bake_of(const std::string& input, const fs::path& out) {
  SCOPED_TRACE(input);
  const Asset asset = load_asset(input);
  BakeOptions o;
  o.plan.out_dir = out.string();
  o.formats = kAllFormats;
  o.plan.frames.fps = modest_fps(asset);
  o.jobs = 2;
  const BakeReport report = bake({input}, o);
  ASSERT_FALSE(report.any_failed()) << report.inputs[0].error;

  // Exactly the planned files are there, and the manifest lists each with its size and digest.
  BakeOptions dry = o;
  dry.dry_run = true;
  std::set<std::string> planned;
  for (const BakeOutput& p : bake({input}, dry).outputs) planned.insert(p.path);
  std::set<std::string> present;
  for (const auto& [rel, bytes] : tree(out, false)) present.insert(rel);
  EXPECT_EQ(present, planned);
  const nlohmann::json manifest = nlohmann::json::parse(read_file(out / "manifest.json"));
  ASSERT_EQ(manifest["outputs"].size(), planned.size());
  for (const auto& entry : manifest["outputs"]) {
    const fs::path file = out / entry["path"].get<std::string>();
    EXPECT_EQ(entry["size"].get<uint64_t>(), fs::file_size(file));
    EXPECT_EQ(entry["sha256"].get<std::string>(), sha256_file(file.string()));
  }
  EXPECT_EQ(manifest["inputs"][0]["sha256"].get<std::string>(), sha256_file(input));
  EXPECT_EQ(manifest["backend"]["name"].get<std::string>(), report.gpu.backend);

  // The deformer bake chose (auto: a hardware GPU's context when there is one, else the fast CPU deformer)
  // run again on the same times gives the same floats as the PLY and VAT files.
  const std::unique_ptr<GpuContext> context = create_hardware_gpu_context();
  const int scene = choose_scene(asset, -1);
  const std::unique_ptr<Deformer> deformer = make_deformer(context.get(), asset, mesh_instances(asset, scene), {});
  for (const auto& clip_entry : manifest["inputs"][0]["animations"]) {
    const std::string folder = clip_entry["folder"].get<std::string>();
    const std::vector<double> times = clip_entry["frame_times"].get<std::vector<double>>();
    const std::vector<int> numbers = clip_entry["frame_numbers"].get<std::vector<int>>();
    const std::string name = clip_entry["name"].get<std::string>();
    const Clip* clip = nullptr;
    for (const Clip& c : asset.clips)
      if (c.name == name) clip = &c;
    int vat_width = 0, vat_height = 0;
    const std::vector<float> vat = read_exr(out / folder / "vat_positions.exr", vat_width, vat_height);
    deformer->run(clip, times, [&](const DeformedBatch& batch) {
      for (size_t k = 0; k < batch.frame_count; ++k) {
        const size_t f = batch.first_frame + k;
        char file[32];
        std::snprintf(file, sizeof file, "frame_%04d.ply", numbers[f]);
        const PlyFile ply = read_ply(out / folder / file);
        size_t v = 0;
        for (const DeformedBatch::Primitive& p : batch.primitives)
          for (size_t i = 0; i < p.vertices; ++i, ++v)
            for (size_t c = 0; c < 3; ++c) {
              const float x = p.positions[(k * p.vertices + i) * 3 + c];
              ASSERT_EQ(ply.vertex_data[v * 8 + c], x) << file << " vertex " << v;
              if (!p.normals.empty()) {
                ASSERT_EQ(ply.vertex_data[v * 8 + 3 + c], p.normals[(k * p.vertices + i) * 3 + c]);
              }
            }
        // VAT texel of vertex v at frame f: (v mod wrap, f · rows + v / wrap), docs/DESIGN.md §4.3.
        const size_t vertices = v;
        ASSERT_GT(vat_width, 0);
        const size_t wrap = size_t(vat_width), rows_per_frame = (vertices + wrap - 1) / wrap;
        ASSERT_EQ(size_t(vat_height), times.size() * rows_per_frame);
        v = 0;
        for (const DeformedBatch::Primitive& p : batch.primitives)
          for (size_t i = 0; i < p.vertices; ++i, ++v) {
            const size_t texel = ((f * rows_per_frame + v / wrap) * wrap + v % wrap) * 4;
            for (size_t c = 0; c < 3; ++c) ASSERT_EQ(vat[texel + c], p.positions[(k * p.vertices + i) * 3 + c]);
          }
      }
    });
  }
}

TEST_F(BakeTest, EveryRigBakesInEveryFormatAndReadsBackAsTheDeformer) {
  for (const char* name : {"twisted_cylinder.gltf", "bending_arm.gltf", "uniform_scale.gltf", "nonuniform_scale.gltf",
                           "eight_influences.gltf", "interpolation_modes.gltf", "morph_skin.gltf", "two_skins.gltf"})
    check_bake_of(rig(name), root_ / name);
}

TEST_F(BakeTest, EverySharedModelBakesInEveryFormatAndReadsBackAsTheDeformer) {
  const std::vector<std::string> models = shared_models();
  if (models.empty()) GTEST_SKIP() << "no shared models at " << DQSKIN_SHARED_TESTDATA_DIR;
  for (const std::string& model : models) check_bake_of(model, root_ / fs::path(model).filename());
}

TEST_F(BakeTest, BoneTextureFileIsTheShadersTexture) {
  const std::string input = rig("nonuniform_scale.gltf");
  BakeOptions o = options("out", unsigned(BakeFormat::kBones));
  ASSERT_FALSE(bake({input}, o).any_failed());
  const Asset asset = load_asset(input);
  const Clip& clip = asset.clips[0];
  const std::vector<double> times = frame_times(clip, o.plan.frames);
  std::vector<JointTransforms> frames;
  for (double t : times) frames.push_back(joint_transforms(asset.skins[0], sample_pose(asset, &clip, t)));
  const BoneTexture expected = pack_bone_texture(frames);
  EXPECT_EQ(expected.texels_per_joint, 5) << "this rig scales a joint";
  const fs::path folder = root_ / "out" / "nonuniform_scale" / (clip.name.empty() ? "animation_0" : clip.name);
  int width = 0, height = 0;
  const std::vector<float> texels = read_exr(folder / "bones_skin0.exr", width, height);
  EXPECT_EQ(size_t(width), expected.width());
  EXPECT_EQ(size_t(height), times.size());
  EXPECT_TRUE(texels == expected.rgba) << "bit for bit";
  const nlohmann::json side = nlohmann::json::parse(read_file(folder / "bones_skin0.json"));
  EXPECT_EQ(side.dump().find("\"texels_per_joint\":5") != std::string::npos ||
                side.dump().find("\"T\":5") != std::string::npos,
            true)
      << side.dump();
}

TEST_F(BakeTest, TwoBakesAreByteIdenticalManifestsIncluded) {
  std::vector<std::string> inputs = {rig("twisted_cylinder.gltf"), rig("two_skins.gltf")};
  for (const std::string& m : shared_models())
    if (m.find("CesiumMan.glb") != std::string::npos) inputs.push_back(m);
  BakeOptions a = options("a"), b = options("b");
  b.jobs = 1;  // and the thread count does not matter
  ASSERT_FALSE(bake(inputs, a).any_failed());
  ASSERT_FALSE(bake(inputs, b).any_failed());
  const auto ta = tree(root_ / "a", true), tb = tree(root_ / "b", true);
  EXPECT_GT(ta.size(), 10u);
  EXPECT_TRUE(ta == tb);
}

TEST_F(BakeTest, ShardsTogetherEqualTheWholeBake) {
  // morph_skin: a skinned mesh with morph targets, whose bone texture's slices sample the midpoints' weights.
  std::vector<std::string> inputs = {rig("twisted_cylinder.gltf"), rig("interpolation_modes.gltf"), rig("two_skins.gltf"),
                                     rig("morph_skin.gltf")};
  for (const std::string& m : shared_models())
    if (m.find("Fox.glb") != std::string::npos) inputs.push_back(m);
  ASSERT_FALSE(bake(inputs, options("whole")).any_failed());
  std::set<std::string> listed;
  for (size_t i = 0; i < 3; ++i) {
    BakeOptions o = options("sharded");
    o.plan.shard = {i, 3};
    const BakeReport r = bake(inputs, o);
    ASSERT_FALSE(r.any_failed());
    EXPECT_TRUE(fs::exists(root_ / "sharded" / ("manifest.shard-" + std::to_string(i) + "-of-3.json")));
    EXPECT_GT(r.outputs.size(), 0u) << "every shard gets work";
    for (const BakeOutput& out : r.outputs) EXPECT_TRUE(listed.insert(out.path).second) << out.path << " baked twice";
  }
  // The textures were cut into slices (docs/DESIGN.md §6.5): the merge assembles their pieces.
  const size_t pieces = size_t(std::count_if(listed.begin(), listed.end(), [](const std::string& p) {
    return p.find(".exr.rows-") != std::string::npos || p.find(".json.template") != std::string::npos;
  }));
  EXPECT_GT(pieces, 0u);
  const MergeReport merged = merge_shards((root_ / "sharded").string());
  ASSERT_TRUE(merged.ok()) << (merged.refusals.empty() ? "" : merged.refusals.front());
  const auto whole = tree(root_ / "whole", true), sharded = tree(root_ / "sharded", true);
  EXPECT_LT(whole.size(), listed.size()) << "fewer files than the pieces";
  EXPECT_TRUE(whole == sharded) << "the shards, merged, equal the whole bake byte for byte, manifest included";
}

// Every texture profile (and a planner budget): two bakes byte-identical, and three shards' files together
// equal to the whole bake.
TEST_F(BakeTest, TextureProfilesAreDeterministicAndShardsUnionToTheWhole) {
  const std::vector<std::string> inputs = {rig("twisted_cylinder.gltf"), rig("two_skins.gltf")};
  const unsigned textures = unsigned(BakeFormat::kVat) | unsigned(BakeFormat::kBones);
  struct Case {
    const char *vat, *bones, *encoding;
    uint64_t max_bytes;
  };
  for (const Case& c : {Case{"openvat", "dq-cocos", "", 0}, Case{"houdini", "mat4", "half", 0},
                        Case{"dqskin", "mat3x4", "png16", 0}, Case{"openvat", "dq", "", 60000}}) {
    SCOPED_TRACE(std::string(c.vat) + " " + c.bones + " " + c.encoding);
    const std::string name = std::string(c.vat) + c.bones + c.encoding + std::to_string(c.max_bytes);
    auto with = [&](const std::string& folder) {
      BakeOptions o = options(name + "/" + folder, textures);
      o.textures.vat_profile = c.vat;
      o.textures.bones_profile = c.bones;
      o.textures.encoding = c.encoding;
      o.textures.max_bytes = c.max_bytes;
      return o;
    };
    const BakeReport first = bake(inputs, with("a"));
    ASSERT_FALSE(first.any_failed()) << first.inputs[0].error << first.inputs[1].error;
    EXPECT_EQ(first.checks.size(), 5u) << "two VATs and three bone textures, each checked";
    ASSERT_FALSE(bake(inputs, with("b")).any_failed());
    for (size_t i = 0; i < 3; ++i) {
      BakeOptions o = with("sharded");
      o.plan.shard = {i, 3};
      ASSERT_FALSE(bake(inputs, o).any_failed());
    }
    const MergeReport merged = merge_shards((root_ / name / "sharded").string());
    ASSERT_TRUE(merged.ok()) << (merged.refusals.empty() ? "" : merged.refusals.front());
    const auto a = tree(root_ / name / "a", true), b = tree(root_ / name / "b", true);
    EXPECT_GT(a.size(), 10u);
    EXPECT_TRUE(a == b) << "byte-identical run to run";
    EXPECT_TRUE(a == tree(root_ / name / "sharded", true)) << "shards, merged, equal the whole";
  }
}

// The diagonal of an asset's bounding box at the rest pose: the size tolerances scale with.
double rest_size(const Asset& asset) {
  const DeformedFrame rest =
      deform_frame(asset, mesh_instances(asset, choose_scene(asset, -1)), sample_pose(asset, nullptr, 0), BlendMode::kDqs);
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const DeformedPrimitive& p : rest.primitives)
    for (const Vec3<double>& v : p.positions) lo = glm::min(lo, v), hi = glm::max(hi, v);
  return glm::length(hi - lo);
}

// Every bone profile on every shared model, baked with the blend the profile implies: the mesh skinned
// from the texture read back lands on the bake's mesh within float rounding (1e-5 of the model's size:
// float texels, 2^-24 relative, through a few dozen float operations in the bake's deformer and the
// profile's model).
TEST_F(BakeTest, EveryBoneProfileSkinsTheSharedModelsAsTheBake) {
  const std::vector<std::string> models = shared_models();
  if (models.empty()) GTEST_SKIP() << "shared test data not found: " << DQSKIN_SHARED_TESTDATA_DIR;
  size_t checked = 0;
  for (const std::string& model : models) {
    const Asset asset = load_asset(model);
    if (asset.skins.empty()) continue;
    const double size = rest_size(asset);
    for (const auto& [profile, mode] : {std::pair{"dq", BlendMode::kDqs}, std::pair{"dq-cocos", BlendMode::kDqs},
                                        std::pair{"mat3x4", BlendMode::kLbs}, std::pair{"mat4", BlendMode::kLbs}}) {
      SCOPED_TRACE(model + " " + profile);
      BakeOptions o = options(std::string("shared_") + profile, unsigned(BakeFormat::kBones));
      o.textures.bones_profile = profile;
      o.mode = mode;
      o.plan.frames.last = 5;  // six frames of each clip (the shortest has six)
      o.overwrite = Overwrite::kReplace;
      const BakeReport r = bake({model}, o);
      ASSERT_FALSE(r.any_failed()) << r.inputs[0].error;
      ASSERT_FALSE(r.checks.empty());
      // Cocos flips each joint to joint 0's side of the quaternion sphere, not each influence to the
      // vertex's heaviest: raylib's robot has vertices (1110 vertex-frames in these six) whose influences
      // then lie on opposite sides, and Cocos blends them the long way round. The check shows it.
      const bool long_way = std::string(profile) == "dq-cocos" && model.find("raylib_robot") != std::string::npos;
      for (const TextureCheck& c : r.checks) {
        if (long_way) EXPECT_GT(c.max_error, 1e-3 * size) << c.clip << " " << c.texture;
        else EXPECT_LE(c.max_error, 1e-5 * size) << c.clip << " " << c.texture;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 20u);
}

// Bone textures in half (--encoding half): every profile within what half's 11 bits allow (2^-10 of the
// model's size: a joint's translation and rotation entries rounded to half, through the blend), and not
// exact, so the half path is the one that ran.
TEST_F(BakeTest, HalfBoneTexturesSkinWithinHalfPrecision) {
  for (const char* rig_name : {"twisted_cylinder.gltf", "nonuniform_scale.gltf", "two_skins.gltf"}) {
    const std::string model = rig(rig_name);
    const Asset asset = load_asset(model);
    const double size = rest_size(asset);
    for (const auto& [profile, mode] : {std::pair{"dq", BlendMode::kDqs}, std::pair{"dq-cocos", BlendMode::kDqs},
                                        std::pair{"mat3x4", BlendMode::kLbs}, std::pair{"mat4", BlendMode::kLbs}}) {
      SCOPED_TRACE(std::string(rig_name) + " " + profile);
      BakeOptions o = options(std::string("half_") + profile, unsigned(BakeFormat::kBones));
      o.textures.bones_profile = profile;
      o.textures.encoding = "half";
      o.mode = mode;
      const BakeReport r = bake({model}, o);
      ASSERT_FALSE(r.any_failed()) << r.inputs[0].error;
      for (const TextureCheck& c : r.checks) {
        EXPECT_LE(c.max_error, std::ldexp(size, -10)) << c.texture;
        EXPECT_GT(c.max_error, 0.0) << c.texture;
      }
      for (const BakeOutput& out : r.outputs) {
        if (!out.path.ends_with(".json")) continue;
        EXPECT_EQ(nlohmann::json::parse(read_file(fs::path(o.plan.out_dir) / out.path))["type"], "float16") << out.path;
      }
    }
  }
}

TEST_F(BakeTest, PlannerDecimatesFramesToFitTheBytes) {
  // The twisted cylinder's twist (31 frames at 30 fps) in 100 kB of half texels: fewer frames, interpolated.
  BakeOptions o = options("planned", unsigned(BakeFormat::kVat));
  o.textures.vat_profile = "openvat";
  o.textures.encoding = "half";
  o.textures.max_bytes = 100000;
  const BakeReport r = bake({rig("twisted_cylinder.gltf")}, o);
  ASSERT_FALSE(r.any_failed()) << r.inputs[0].error;
  const nlohmann::json side = nlohmann::json::parse(read_file(root_ / "planned/twisted_cylinder/twist/vat.json"));
  const size_t frames = frame_times(load_asset(rig("twisted_cylinder.gltf")).clips[0], o.plan.frames).size();
  EXPECT_LT(side["frame_count"].get<size_t>(), frames);
  EXPECT_GT(side["plan"]["frame_step"].get<size_t>(), 1u);
  EXPECT_LE(side["plan"]["gpu_bytes"].get<uint64_t>(), 100000u);
  EXPECT_EQ(side["fps"].get<double>(), 30.0 / side["plan"]["frame_step"].get<double>());
  // The check, at the texture's frames and midpoints, stays within what the planner expected.
  EXPECT_LE(side["decode_check"]["max_midpoint_error"].get<double>(), side["plan"]["expected_error"].get<double>() * 1.001);
  EXPECT_LE(side["decode_check"]["max_error"].get<double>(), side["plan"]["encoding_error"].get<double>());
}

TEST_F(BakeTest, AnErrorBudgetNoChoiceMeetsFailsTheInputAndLeavesNoTexture) {
  // png8 cannot hold the twist within 10 µm: the planner says so with the figures, nothing is written.
  BakeOptions o = options("refused", unsigned(BakeFormat::kVat) | unsigned(BakeFormat::kPly));
  o.textures.encoding = "png8";
  o.textures.max_error = 1e-5;
  const BakeReport r = bake({rig("twisted_cylinder.gltf")}, o);
  ASSERT_TRUE(r.any_failed());
  EXPECT_NE(r.inputs[0].error.find("clip twist: no texture meets --max-error 10 um; the most accurate is png8 at 30 fps (9.01 mm"),
            std::string::npos)
      << r.inputs[0].error;
  EXPECT_FALSE(fs::exists(root_ / "refused" / "twisted_cylinder")) << "nothing under a final name";
  // The dry run shows the same refusal, and with a reachable budget the table of choices.
  o.dry_run = true;
  EXPECT_TRUE(bake({rig("twisted_cylinder.gltf")}, o).any_failed());
  o.textures.max_error = 0.05;
  const BakeReport dry = bake({rig("twisted_cylinder.gltf")}, o);
  ASSERT_FALSE(dry.any_failed()) << dry.inputs[0].error;
  ASSERT_FALSE(dry.plans.empty());
  EXPECT_EQ(std::count_if(dry.plans.begin(), dry.plans.end(),
                          [](const std::string& l) { return l.find("<- chosen") != std::string::npos; }),
            1);
}

TEST_F(BakeTest, BoneTextureMissingTheErrorBudgetLeavesNoTexture) {
  // mat4 is LBS: the twisted cylinder's candy wrapper is half a unit from DQS, over a 1 mm budget.
  BakeOptions o = options("bones", unsigned(BakeFormat::kBones));
  o.textures.bones_profile = "mat4";
  o.textures.max_error = 1e-3;
  const BakeReport r = bake({rig("twisted_cylinder.gltf")}, o);
  ASSERT_TRUE(r.any_failed());
  EXPECT_NE(r.inputs[0].error.find("clip twist, bones_skin0: the texture skins (lbs) to within 50 cm of the deformed "
                                   "mesh (--mode dqs), over --max-error 1 mm"),
            std::string::npos)
      << r.inputs[0].error;
  EXPECT_FALSE(fs::exists(root_ / "bones" / "twisted_cylinder"));
  // Baked with LBS, the same texture passes.
  o.mode = BlendMode::kLbs;
  const BakeReport lbs = bake({rig("twisted_cylinder.gltf")}, o);
  ASSERT_FALSE(lbs.any_failed()) << lbs.inputs[0].error;
  ASSERT_EQ(lbs.checks.size(), 1u);
  EXPECT_LT(lbs.checks[0].max_error, 1e-6);
}

TEST_F(BakeTest, DifferentExistingOutputIsRefusedUnlessForced) {
  const std::string input = rig("bending_arm.gltf");
  BakeOptions o = options("out", unsigned(BakeFormat::kPly));
  ASSERT_FALSE(bake({input}, o).any_failed());
  const auto before = tree(root_ / "out", false);
  // A rerun finds equal files and leaves them alone.
  const BakeReport again = bake({input}, o);
  ASSERT_FALSE(again.any_failed());
  for (const BakeOutput& out : again.outputs) EXPECT_TRUE(out.unchanged) << out.path;

  const fs::path victim = root_ / "out" / before.begin()->first;
  std::ofstream(victim, std::ios::binary | std::ios::app) << "edited";
  const BakeReport refused = bake({input}, o);
  ASSERT_TRUE(refused.any_failed());
  EXPECT_EQ(refused.inputs[0].error, victim.string() + ": exists with different contents; not overwritten");
  EXPECT_EQ(read_file(victim), before.begin()->second + "edited");

  o.overwrite = Overwrite::kReplace;
  ASSERT_FALSE(bake({input}, o).any_failed());
  EXPECT_TRUE(tree(root_ / "out", false) == before);
}

TEST_F(BakeTest, FailingInputIsReportedAndTheOthersBake) {
  const BakeReport r = bake({rig("no_such_rig.gltf"), rig("bending_arm.gltf")}, options("out", unsigned(BakeFormat::kPly)));
  ASSERT_EQ(r.inputs.size(), 2u);
  EXPECT_NE(r.inputs[0].error, "");
  EXPECT_EQ(r.inputs[1].error, "");
  EXPECT_TRUE(fs::exists(root_ / "out" / "bending_arm"));
  const nlohmann::json manifest = nlohmann::json::parse(read_file(root_ / "out" / "manifest.json"));
  EXPECT_EQ(manifest["inputs"][0]["error"].get<std::string>(), r.inputs[0].error);
}

TEST_F(BakeTest, InputsWritingToTheSameFolderAreRefusedBeforeAnythingIsWritten) {
  const fs::path other = root_ / "elsewhere";
  fs::create_directories(other);
  fs::copy_file(rig("bending_arm.gltf"), other / "bending_arm.gltf");
  try {
    bake({rig("bending_arm.gltf"), (other / "bending_arm.gltf").string()}, options("out"));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("would both write to"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(root_ / "out"));
}

TEST_F(BakeTest, DryRunListsAndWritesNothing) {
  BakeOptions o = options("out", unsigned(BakeFormat::kGlb) | unsigned(BakeFormat::kVat));
  o.dry_run = true;
  o.plan.frames.fps = 4;
  const BakeReport r = bake({rig("two_skins.gltf")}, o);
  EXPECT_FALSE(fs::exists(root_ / "out"));
  ASSERT_FALSE(r.outputs.empty());
  EXPECT_EQ(r.outputs.front().path.rfind("two_skins/", 0), 0u);
  const Asset asset = load_asset(rig("two_skins.gltf"));
  EXPECT_EQ(r.outputs.size(), frame_times(asset.clips[0], o.plan.frames).size() + 4)
      << "frames + vat (2 EXR, the rest mesh, 1 JSON)";
}

TEST_F(BakeTest, DibBakesOnTheCpuReference) {
  BakeOptions o = options("out", unsigned(BakeFormat::kPly));
  o.mode = BlendMode::kDib;
  const BakeReport r = bake({rig("twisted_cylinder.gltf")}, o);
  ASSERT_FALSE(r.any_failed()) << r.inputs[0].error;
  EXPECT_EQ(r.gpu.backend, "cpu");
  o.backend = Backend::kEgl;
  EXPECT_THROW(bake({rig("twisted_cylinder.gltf")}, o), InputError);
}

TEST(ParseBakeFormats, KnowsTheFiveFormats) {
  EXPECT_EQ(parse_bake_formats("glb,ply,obj,vat,bones"), kAllFormats);
  EXPECT_EQ(parse_bake_formats("vat"), unsigned(BakeFormat::kVat));
  EXPECT_THROW(parse_bake_formats("gltf"), InputError);
  EXPECT_THROW(parse_bake_formats("glb,"), InputError);
}

}  // namespace
}  // namespace dqskin
