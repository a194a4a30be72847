// The checks of `dqskin lint`: each file of the bad-skin catalogue (testdata/bad_skins/, written by
// scripts/testdata/make_bad_skins.py) shows its one problem and nothing else, with the right worst example; the
// tolerances; unreadable files; the reports.
#include "dqskin/lint.hpp"

#include "lint_checks.hpp"
#include "../test_support/scratch_dir.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace dqskin {
namespace {

std::string catalogue(const std::string& name) {
  return (std::filesystem::path(DQSKIN_TESTDATA_DIR) / "bad_skins" / name).string();
}

// A catalogue file, the one check it must show (none for the clean file) and its worst example.
struct Case {
  const char* file;
  const char* check;
  long long vertex, joint, key;
  double value;
};

const Case kCases[] = {
    {"clean.gltf", nullptr, -1, -1, -1, 0},
    {"weights_sum_float.gltf", "weight-sum", 6, -1, -1, 0.75},
    {"weights_sum_ubyte.gltf", "weight-sum", 10, -1, -1, 230.0 / 255},
    {"weights_sum_ushort.gltf", "weight-sum", 10, -1, -1, 70000.0 / 65535},
    {"five_influences.gltf", "too-many-influences", 8, -1, -1, 5},
    {"nine_influences.gltf", "over-8-influences", 8, -1, -1, 9},
    {"zero_weight_vertex.gltf", "zero-weight-vertex", 7, -1, -1, 0},
    {"negative_weight.gltf", "negative-weight", 9, 5, -1, -0.25},
    {"duplicate_joint.gltf", "duplicate-joint", 11, 5, -1, 1.0},
    {"joint_out_of_range.gltf", "joint-out-of-range", 13, 12, -1, 12},
    {"unused_joint.gltf", "unused-joint", -1, 10, -1, 11},  // value: the joint's node
    {"no_common_root.gltf", "no-common-root", -1, 10, -1, 11},
    {"skeleton_not_root.gltf", "skeleton-not-root", -1, 0, -1, 6},
    {"wrong_inverse_bind.gltf", "inverse-bind-mismatch", -1, 4, -1, 0.25 / 4.5},  // over the skeleton's size
    {"nonuniform_scaled_joint.gltf", "joint-nonuniform-scale", -1, 6, -1, 0.5},
    {"uniform_scaled_joint.gltf", "joint-uniform-scale", -1, 6, -1, 0.5},
    // Legal: joint 9 scaled at rest and its inverse bind matrix scaling back make an identity joint matrix.
    {"non_orthonormal_ibm.gltf", nullptr, -1, -1, -1, 0},
    {"non_unit_rotation_keys.gltf", "rotation-not-unit", -1, -1, 1, 1.25},
    {"hemisphere_flip_keys.gltf", "hemisphere-flip", -1, -1, 1, -0.984808},
    {"hemisphere_flip_cubic.gltf", "hemisphere-flip", -1, -1, 1, -0.984808},
};

class Catalogue : public ::testing::TestWithParam<Case> {};

TEST_P(Catalogue, FindsItsProblemAndNothingElse) {
  const Case& c = GetParam();
  const LintFileResult r = lint_file(catalogue(c.file), {});
  ASSERT_EQ(r.error, "");
  if (!c.check) {
    EXPECT_TRUE(r.findings.empty()) << lint_text({r});
    return;
  }
  ASSERT_EQ(r.findings.size(), 1u) << lint_text({r});
  const LintFinding& f = r.findings.front();
  EXPECT_EQ(f.check, c.check);
  EXPECT_EQ(f.worst.vertex, c.vertex) << f.message;
  EXPECT_EQ(f.worst.joint, c.joint) << f.message;
  EXPECT_EQ(f.worst.key, c.key) << f.message;
  EXPECT_NEAR(f.worst.value, c.value, 1e-5) << f.message;
  bool listed = false;
  for (const LintCheckInfo& info : lint_checks())
    if (f.check == info.id) {
      listed = true;
      EXPECT_EQ(f.severity, info.severity);
    }
  EXPECT_TRUE(listed) << f.check;
}

INSTANTIATE_TEST_SUITE_P(BadSkins, Catalogue, ::testing::ValuesIn(kCases), [](const ::testing::TestParamInfo<Case>& p) {
  return std::filesystem::path(p.param.file).stem().string();
});

TEST(LintCounts, CountsEveryCaseAndKeepsTheFirstOfEqualWorst) {
  // Two flips of equal size (keys 0-1 and 1-2): both counted, the first is the example.
  const LintFileResult flips = lint_file(catalogue("hemisphere_flip_keys.gltf"), {});
  ASSERT_EQ(flips.findings.size(), 1u);
  EXPECT_EQ(flips.findings[0].count, 2u);
  // Joint 6 scaled: it and its three descendants have scaled joint matrices, each counted once over all keys.
  const LintFileResult scaled = lint_file(catalogue("nonuniform_scaled_joint.gltf"), {});
  ASSERT_EQ(scaled.findings.size(), 1u);
  EXPECT_EQ(scaled.findings[0].count, 4u);
}

// An in-memory primitive: one vertex, one set.
gltf::SkinData one_vertex(int weights_component, std::vector<double> weights, std::vector<uint32_t> joints) {
  gltf::SkinData d;
  d.structure.nodes.resize(4);
  for (int n = 1; n < 4; ++n) d.structure.nodes[size_t(n)].parent = n - 1;
  Skin skin;
  skin.joints = {0, 1, 2, 3};
  skin.inverse_bind.assign(4, Mat4<double>(1.0));
  d.structure.skins.push_back(skin);
  gltf::SkinnedPrimitive p;
  p.vertices = 1;
  p.positions = {glm::vec3(0.0f)};
  p.sets.push_back({gltf::kComponentUnsignedByte, weights_component, std::move(joints), std::move(weights)});
  p.skins = {0};
  d.primitives.push_back(p);
  return d;
}

TEST(LintWeightSum, NormalizedBytesMayBeOffByTheirRounding) {
  // 128 + 128 = 256 of 255: 1/255 over, within 2 · 0.5/255 for two stored weights.
  lint::Findings bytes;
  lint::check_influences(one_vertex(gltf::kComponentUnsignedByte, {128 / 255.0, 128 / 255.0, 0, 0}, {0, 1, 0, 0}), {},
                         bytes);
  EXPECT_EQ(bytes.count("weight-sum"), 0u);
  // The same sum in float is beyond --sum-tolerance.
  lint::Findings floats;
  lint::check_influences(one_vertex(gltf::kComponentFloat, {128 / 255.0, 128 / 255.0, 0, 0}, {0, 1, 0, 0}), {}, floats);
  ASSERT_EQ(floats.count("weight-sum"), 1u);
  EXPECT_NEAR(floats["weight-sum"].worst.value, 256 / 255.0, 1e-12);
  // And within a looser one.
  LintOptions loose;
  loose.sum_tolerance = 0.01;
  lint::Findings loosened;
  lint::check_influences(one_vertex(gltf::kComponentFloat, {128 / 255.0, 128 / 255.0, 0, 0}, {0, 1, 0, 0}), loose,
                         loosened);
  EXPECT_EQ(loosened.count("weight-sum"), 0u);
}

TEST(LintInfluences, ZeroWeightDuplicatesAreNotDuplicates) {
  // Joint 0 in two slots, but one of them with weight 0 (the usual padding): no duplicate.
  lint::Findings f;
  lint::check_influences(one_vertex(gltf::kComponentFloat, {1, 0, 0, 0}, {0, 0, 0, 0}), {}, f);
  EXPECT_EQ(f.count("duplicate-joint"), 0u);
  EXPECT_EQ(f.count("weight-sum"), 0u);
}

TEST(LintInfluences, CountsAVertexOnceHoweverManySlotsShareItsProblem) {
  // Joint 1 three times, joint 9 (beyond the skin's 4 joints) in the last slot, and 7 beyond too: one
  // vertex each, the worst case kept.
  lint::Findings dup;
  lint::check_influences(one_vertex(gltf::kComponentFloat, {0.25, 0.25, 0.5, 0}, {1, 1, 1, 0}), {}, dup);
  ASSERT_EQ(dup.count("duplicate-joint"), 1u);
  EXPECT_EQ(dup.at("duplicate-joint").count, 1u);
  lint::Findings beyond;
  lint::check_influences(one_vertex(gltf::kComponentFloat, {0.5, 0.1, 0, 0.4}, {0, 7, 0, 9}), {}, beyond);
  ASSERT_EQ(beyond.count("joint-out-of-range"), 1u);
  EXPECT_EQ(beyond.at("joint-out-of-range").count, 1u);
  EXPECT_EQ(beyond.at("joint-out-of-range").worst.joint, 9);
}

// The clean catalogue file with its primitive's influence attributes replaced, written into `dir`.
std::string with_influence_sets(const std::filesystem::path& dir, const std::vector<int>& sets) {
  std::ifstream in(catalogue("clean.gltf"));
  nlohmann::json doc = nlohmann::json::parse(in);
  nlohmann::json& attributes = doc["meshes"][0]["primitives"][0]["attributes"];
  const nlohmann::json joints = attributes["JOINTS_0"], weights = attributes["WEIGHTS_0"];
  attributes.erase("JOINTS_0");
  attributes.erase("WEIGHTS_0");
  for (int n : sets) {
    attributes["JOINTS_" + std::to_string(n)] = joints;
    attributes["WEIGHTS_" + std::to_string(n)] = weights;
  }
  const std::filesystem::path path = dir / "sets.gltf";
  std::ofstream(path) << doc.dump();
  return path.string();
}

TEST(LintFile, RefusesMoreThanEightSetsAndGapsInTheirNumbers) {
  const testing_support::ScratchDir dir("lint");
  // Nine sets naming one accessor pair: a few bytes of JSON that would decode to 9 times the data.
  const LintFileResult nine = lint_file(with_influence_sets(dir.path(), {0, 1, 2, 3, 4, 5, 6, 7, 8}), {});
  EXPECT_NE(nine.error.find("JOINTS_8/WEIGHTS_8: more than 32 influences per vertex"), std::string::npos) << nine.error;
  const LintFileResult gap = lint_file(with_influence_sets(dir.path(), {0, 2}), {});
  EXPECT_NE(gap.error.find("but not JOINTS_1 or WEIGHTS_1"), std::string::npos) << gap.error;
  // Eight sets are read (and their repeated joints found).
  const LintFileResult eight = lint_file(with_influence_sets(dir.path(), {0, 1, 2, 3, 4, 5, 6, 7}), {});
  EXPECT_EQ(eight.error, "");
  EXPECT_TRUE(eight.has("duplicate-joint"));
}

TEST(LintInfluences, MaxInfluencesMovesTheWarning) {
  const LintFileResult four = lint_file(catalogue("five_influences.gltf"), {});
  EXPECT_TRUE(four.has("too-many-influences"));
  LintOptions eight;
  eight.max_influences = 8;
  EXPECT_FALSE(lint_file(catalogue("five_influences.gltf"), eight).has("too-many-influences"));
}

TEST(LintFile, UnreadableFileIsAnErrorNotAnException) {
  const LintFileResult missing = lint_file(catalogue("no_such_file.gltf"), {});
  EXPECT_NE(missing.error, "");
  EXPECT_EQ(missing.worst(), LintSeverity::kError);
  const LintFileResult text = lint_file((std::filesystem::path(DQSKIN_TESTDATA_DIR) / "README.md").string(), {});
  EXPECT_NE(text.error, "");
  EXPECT_EQ(text.error.find('\n'), std::string::npos);
}

TEST(LintReports, JsonAndJUnitHoldEveryFileAndCheck) {
  const std::vector<LintFileResult> results = {lint_file(catalogue("clean.gltf"), {}),
                                               lint_file(catalogue("negative_weight.gltf"), {}),
                                               lint_file(catalogue("no_such_file.gltf"), {})};
  const nlohmann::json doc = nlohmann::json::parse(lint_json(results, {}));
  ASSERT_EQ(doc["files"].size(), 3u);
  EXPECT_EQ(doc["files"][0]["status"], "clean");
  EXPECT_EQ(doc["files"][1]["findings"][0]["check"], "negative-weight");
  EXPECT_EQ(doc["files"][1]["findings"][0]["worst"]["vertex"], 9);
  EXPECT_TRUE(doc["files"][1]["findings"][0]["worst"]["key"].is_null());
  EXPECT_TRUE(doc["files"][2].contains("problem"));
  EXPECT_EQ(doc["summary"]["status"], "error");
  EXPECT_EQ(doc["summary"]["error"], 2);

  const std::string junit = lint_junit(results);
  const size_t checks = lint_checks().size();
  // Two readable files × every check, and one testcase for the unreadable one; two failures.
  EXPECT_NE(junit.find("tests=\"" + std::to_string(2 * checks + 1) + "\" failures=\"2\""), std::string::npos) << junit;
  EXPECT_EQ(lint_junit(results), junit);  // deterministic
  EXPECT_EQ(lint_text(results), lint_text(results));
}

}  // namespace
}  // namespace dqskin
