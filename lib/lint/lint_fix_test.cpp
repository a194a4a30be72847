// `dqskin lint --fix`: every fixable problem of the bad-skin catalogue is gone when the fixed file is
// linted again, the others stay; normalized weights are stored summing exactly to 255 or 65535; influences
// are sorted and cut; rotation keys are unit and in one hemisphere; the output is deterministic.
#include "dqskin/lint.hpp"

#include "../load/skin_data.hpp"
#include "dqskin/error.hpp"
#include "dqskin/job.hpp"
#include "../test_support/read_file.hpp"
#include "../test_support/scratch_dir.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace dqskin {
namespace {

using testing_support::ScratchDir;

std::string catalogue(const std::string& name) {
  return (std::filesystem::path(DQSKIN_TESTDATA_DIR) / "bad_skins" / name).string();
}

struct FixCase {
  const char* file;
  const char* check;
  bool fixable;
};

const FixCase kFixCases[] = {
    {"weights_sum_float.gltf", "weight-sum", true},
    {"weights_sum_ubyte.gltf", "weight-sum", true},
    {"weights_sum_ushort.gltf", "weight-sum", true},
    {"five_influences.gltf", "too-many-influences", true},
    {"nine_influences.gltf", "over-8-influences", true},
    {"zero_weight_vertex.gltf", "zero-weight-vertex", true},
    {"negative_weight.gltf", "negative-weight", true},
    {"duplicate_joint.gltf", "duplicate-joint", true},
    {"joint_out_of_range.gltf", "joint-out-of-range", true},
    {"skeleton_not_root.gltf", "skeleton-not-root", true},
    {"non_unit_rotation_keys.gltf", "rotation-not-unit", true},
    {"hemisphere_flip_keys.gltf", "hemisphere-flip", true},
    {"hemisphere_flip_cubic.gltf", "hemisphere-flip", true},
    {"unused_joint.gltf", "unused-joint", false},
    {"no_common_root.gltf", "no-common-root", false},
    {"wrong_inverse_bind.gltf", "inverse-bind-mismatch", false},
    {"nonuniform_scaled_joint.gltf", "joint-nonuniform-scale", false},
};

class FixCatalogue : public ::testing::TestWithParam<FixCase> {};

TEST_P(FixCatalogue, FixableProblemsAreGoneOthersStay) {
  const FixCase& c = GetParam();
  ScratchDir dir("lint_fix");
  const std::string out = (dir.path() / "fixed.glb").string();
  lint_fix(catalogue(c.file), out, {});
  const LintFileResult again = lint_file(out, {});
  ASSERT_EQ(again.error, "");
  EXPECT_EQ(again.has(c.check), !c.fixable) << lint_text({again});
  if (c.fixable) {
    EXPECT_TRUE(again.findings.empty()) << lint_text({again});
  }
}

INSTANTIATE_TEST_SUITE_P(BadSkins, FixCatalogue, ::testing::ValuesIn(kFixCases),
                         [](const ::testing::TestParamInfo<FixCase>& p) {
                           return std::filesystem::path(p.param.file).stem().string();
                         });

TEST(LintFix, NormalizedWeightsSumExactlyInTheirOwnType) {
  // The broken vertex 10: 200 and 30 of 255, or 60000 and 10000 of 65535; fixed, the same shares of 1.
  for (const auto& [file, component, scale, share] : {std::tuple{"weights_sum_ubyte.gltf", 5121, 255.0, 200.0 / 230},
                                                      std::tuple{"weights_sum_ushort.gltf", 5123, 65535.0, 6.0 / 7}}) {
    ScratchDir dir("lint_fix");
    const std::string out = (dir.path() / "fixed.glb").string();
    lint_fix(catalogue(file), out, {});
    const gltf::SkinData d = gltf::read_skin_data(out, {});
    ASSERT_EQ(d.primitives.size(), 1u);
    ASSERT_EQ(d.primitives[0].sets.size(), 1u);
    const gltf::InfluenceSet& set = d.primitives[0].sets[0];
    EXPECT_EQ(set.weights_component, component);
    for (size_t v = 0; v < d.primitives[0].vertices; ++v) {
      long total = 0;
      for (size_t k = 0; k < 4; ++k) {
        total += std::lround(set.weights[4 * v + k] * scale);
        if (k > 0) {
          EXPECT_GE(set.weights[4 * v + k - 1], set.weights[4 * v + k]) << "vertex " << v;  // sorted
        }
      }
      EXPECT_EQ(total, long(scale)) << file << " vertex " << v;
    }
    EXPECT_NEAR(set.weights[4 * 10], share, 1 / scale) << file;
    EXPECT_EQ(set.joints[4 * 10], 5u);
  }
}

TEST(LintFix, InfluencesAreCutToTheLargestAndRenormalized) {
  ScratchDir dir("lint_fix");
  const std::string out = (dir.path() / "fixed.glb").string();
  lint_fix(catalogue("nine_influences.gltf"), out, {});
  const gltf::SkinData d = gltf::read_skin_data(out, {});
  ASSERT_EQ(d.primitives[0].sets.size(), 1u);  // four kept: JOINTS_1 and JOINTS_2 go
  const gltf::InfluenceSet& set = d.primitives[0].sets[0];
  // Vertex 8 had 0.125 on joints 0-6 and 0.0625 on 7 and 8: the first four of the 0.125s (ties by joint).
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(set.joints[4 * 8 + k], k);
    EXPECT_NEAR(set.weights[4 * 8 + k], 0.25, 1e-7);
  }
  LintOptions eight;
  eight.max_influences = 8;
  lint_fix(catalogue("nine_influences.gltf"), out, eight);
  EXPECT_EQ(gltf::read_skin_data(out, {}).primitives[0].sets.size(), 2u);  // eight kept: JOINTS_1 stays
}

TEST(LintFix, ZeroWeightVertexGoesToTheNearestJoint) {
  ScratchDir dir("lint_fix");
  const std::string out = (dir.path() / "fixed.glb").string();
  lint_fix(catalogue("zero_weight_vertex.gltf"), out, {});
  const gltf::SkinData fixed = gltf::read_skin_data(out, {});
  const gltf::InfluenceSet& set = fixed.primitives[0].sets[0];
  EXPECT_EQ(set.joints[4 * 7], 3u);  // vertex 7 sits at x = 1.5, joint 3's place
  EXPECT_EQ(set.weights[4 * 7], 1.0);
}

TEST(LintFix, RotationKeysAreUnitAndInOneHemisphere) {
  for (const char* file : {"hemisphere_flip_keys.gltf", "non_unit_rotation_keys.gltf"}) {
    ScratchDir dir("lint_fix");
    const std::string out = (dir.path() / "fixed.glb").string();
    lint_fix(catalogue(file), out, {});
    const gltf::SkinData d = gltf::read_skin_data(out, {});
    const Channel& ch = d.structure.clips[0].channels[0];
    for (size_t k = 0; k < ch.times.size(); ++k) {
      double length = 0, dot = 0;
      for (size_t i = 0; i < 4; ++i) {
        length += double(ch.values[4 * k + i]) * double(ch.values[4 * k + i]);
        if (k > 0) dot += double(ch.values[4 * k + i]) * double(ch.values[4 * (k - 1) + i]);
      }
      EXPECT_NEAR(std::sqrt(length), 1.0, 1e-6) << file << " key " << k;
      EXPECT_GE(dot, 0.0) << file << " key " << k;
    }
  }
}

TEST(LintFix, CubicSplineTangentsTurnWithTheirKey) {
  // Key 1 was stored negated, its tangents a tenth of it: after the fix all three are negated back.
  ScratchDir dir("lint_fix");
  const std::string out = (dir.path() / "fixed.glb").string();
  lint_fix(catalogue("hemisphere_flip_cubic.gltf"), out, {});
  const gltf::SkinData before = gltf::read_skin_data(catalogue("hemisphere_flip_cubic.gltf"), {});
  const gltf::SkinData after = gltf::read_skin_data(out, {});
  const Channel& a = before.structure.clips[0].channels[0];
  const Channel& b = after.structure.clips[0].channels[0];
  ASSERT_EQ(b.interpolation, Interpolation::kCubicSpline);
  ASSERT_EQ(a.values.size(), b.values.size());
  for (size_t i = 0; i < a.values.size(); ++i) {
    const bool key1 = i / 12 == 1;  // in-tangent, value, out-tangent of key 1
    EXPECT_FLOAT_EQ(b.values[i], key1 ? -a.values[i] : a.values[i]) << "component " << i;
  }
  EXPECT_GT(b.values[12 + 4 + 3], 0.0f);  // the value's w and its in-tangent's are positive again
  EXPECT_GT(b.values[12 + 3], 0.0f);
}

// The catalogue's rig with its rotation channel's times and keys replaced (x, y, z, w per key; CUBICSPLINE:
// in-tangent, value, out-tangent), in an external buffer beside the .gltf written to `dir`; `rest`, when
// given, the animated node's rotation at rest.
std::string rig_with_rotation_keys(const ScratchDir& dir, const std::vector<float>& times,
                                   const std::vector<float>& keys, const char* interpolation,
                                   const std::vector<double>& rest = {}) {
  std::ifstream in(catalogue("non_unit_rotation_keys.gltf"));
  nlohmann::json doc = nlohmann::json::parse(in);
  std::ofstream(dir.path() / "keys.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(times.data()), std::streamsize(times.size() * sizeof(float)))
      .write(reinterpret_cast<const char*>(keys.data()), std::streamsize(keys.size() * sizeof(float)));
  const size_t buffer = doc["buffers"].size(), view = doc["bufferViews"].size(), accessor = doc["accessors"].size();
  doc["buffers"].push_back({{"uri", "keys.bin"}, {"byteLength", (times.size() + keys.size()) * sizeof(float)}});
  doc["bufferViews"].push_back({{"buffer", buffer}, {"byteLength", times.size() * sizeof(float)}});
  doc["bufferViews"].push_back(
      {{"buffer", buffer}, {"byteOffset", times.size() * sizeof(float)}, {"byteLength", keys.size() * sizeof(float)}});
  doc["accessors"].push_back({{"bufferView", view}, {"componentType", 5126}, {"count", times.size()},
                              {"type", "SCALAR"}, {"min", {times.front()}}, {"max", {times.back()}}});
  doc["accessors"].push_back({{"bufferView", view + 1}, {"componentType", 5126}, {"count", keys.size() / 4},
                              {"type", "VEC4"}});
  nlohmann::json& sampler = doc["animations"][0]["samplers"][0];
  sampler = {{"input", accessor}, {"output", accessor + 1}, {"interpolation", interpolation}};
  const int node = doc["animations"][0]["channels"][0]["target"]["node"];
  if (!rest.empty()) doc["nodes"][size_t(node)]["rotation"] = rest;
  const std::string path = (dir.path() / "keys.gltf").string();
  std::ofstream(path) << doc.dump();
  return path;
}

// The fixed file's first rotation channel: its keys, 4 floats each (CUBICSPLINE: 12).
std::vector<float> fixed_keys(const std::string& input, const ScratchDir& dir) {
  const std::string out = (dir.path() / "fixed.glb").string();
  lint_fix(input, out, {});
  const LintFileResult again = lint_file(out, {});
  EXPECT_FALSE(again.has("rotation-not-unit")) << lint_text({again});
  return gltf::read_skin_data(out, {}).structure.clips[0].channels[0].values;
}

const float kHalf = float(std::sqrt(0.5));

TEST(LintFix, ZeroRotationKeyTakesTheNearestValidKeyOfItsChannel) {
  // Key 1 is (0, 0, 0, 0) between the identity and a quarter turn about z; which neighbour is nearer in
  // time decides, the earlier one when both are as near.
  const std::vector<float> keys = {0, 0, 0, 1, 0, 0, 0, 0, 0, 0, kHalf, kHalf};
  for (const auto& [middle, expected] : {std::pair{0.2f, std::vector<float>{0, 0, 0, 1}},
                                         {0.8f, {0, 0, kHalf, kHalf}},
                                         {0.5f, {0, 0, 0, 1}}}) {
    ScratchDir dir("lint_fix");
    const std::vector<float> fixed = fixed_keys(rig_with_rotation_keys(dir, {0, middle, 1}, keys, "LINEAR"), dir);
    ASSERT_EQ(fixed.size(), 12u);
    for (size_t i = 0; i < 4; ++i) EXPECT_FLOAT_EQ(fixed[4 + i], expected[i]) << "key at " << middle;
  }
  // Zero keys at both ends have one valid neighbour each.
  ScratchDir dir("lint_fix");
  const std::vector<float> ends = {0, 0, 0, 0, 0, 0, kHalf, kHalf, 0, 0, 0, 0};
  const std::vector<float> fixed = fixed_keys(rig_with_rotation_keys(dir, {0, 0.5f, 1}, ends, "LINEAR"), dir);
  ASSERT_EQ(fixed.size(), 12u);
  for (size_t i = 0; i < 12; ++i) EXPECT_FLOAT_EQ(fixed[i], ends[4 + i % 4]) << "component " << i;
}

TEST(LintFix, AllZeroRotationChannelTakesTheNodesRestRotation) {
  ScratchDir dir("lint_fix");
  const std::vector<float> zeros(12, 0.0f);
  const std::vector<float> fixed =
      fixed_keys(rig_with_rotation_keys(dir, {0, 0.5f, 1}, zeros, "LINEAR", {0, 0, std::sqrt(0.5), std::sqrt(0.5)}), dir);
  ASSERT_EQ(fixed.size(), 12u);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_FLOAT_EQ(fixed[4 * k + 2], kHalf) << "key " << k;
    EXPECT_FLOAT_EQ(fixed[4 * k + 3], kHalf) << "key " << k;
  }
}

TEST(LintFix, ZeroCubicSplineKeyTakesItsNeighbourWithZeroTangents) {
  ScratchDir dir("lint_fix");
  // Key 1's value is (0, 0, 0, 0), its tangents are not: it becomes key 0's value, resting (zero tangents).
  const std::vector<float> keys = {0, 0, 0, 0,   0, 0, 0, 1,   0, 0, 0.1f, 0,
                                   0, 0, 0.1f, 0, 0, 0, 0, 0,   0, 0, 0.1f, 0,
                                   0, 0, 0.1f, 0, 0, 0, kHalf, kHalf, 0, 0, 0, 0};
  const std::vector<float> fixed = fixed_keys(rig_with_rotation_keys(dir, {0, 0.5f, 1}, keys, "CUBICSPLINE"), dir);
  ASSERT_EQ(fixed.size(), 36u);
  const std::vector<float> expected = {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0};
  for (size_t i = 0; i < 12; ++i) EXPECT_FLOAT_EQ(fixed[12 + i], expected[i]) << "component " << i;
}

TEST(LintFix, SameInputSameBytes) {
  ScratchDir dir("lint_fix");
  const std::string a = (dir.path() / "a.glb").string(), b = (dir.path() / "b.glb").string();
  lint_fix(catalogue("five_influences.gltf"), a, {});
  lint_fix(catalogue("five_influences.gltf"), b, {});
  EXPECT_EQ(testing_support::read_file(a), testing_support::read_file(b));
}

TEST(LintFix, StopsWhenCancelledLeavingNothing) {
  ScratchDir dir("lint_fix");
  const std::string out = (dir.path() / "fixed.glb").string();
  std::atomic<bool> cancel{true};
  LintOptions options;
  options.cancel = &cancel;
  EXPECT_THROW(lint_fix(catalogue("five_influences.gltf"), out, options), JobCancelled);
  EXPECT_THROW(lint_file(catalogue("five_influences.gltf"), options), JobCancelled);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << "no output and no temporary";
}

TEST(LintFix, RefusesWhatItCannotRead) {
  ScratchDir dir("lint_fix");
  const std::string out = (dir.path() / "fixed.glb").string();
  EXPECT_THROW(lint_fix(catalogue("no_such_file.gltf"), out, {}), InputError);
  EXPECT_FALSE(std::filesystem::exists(out));
  LintOptions past_cap;  // more than the loader reads (asset.hpp), so more than a fix could keep
  past_cap.max_influences = kMaxInfluences + 1;
  EXPECT_THROW(lint_fix(catalogue("clean.gltf"), out, past_cap), InputError);
}

}  // namespace
}  // namespace dqskin
