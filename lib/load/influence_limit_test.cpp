// Reading every influence set, and LoadOptions::max_influences (--max-influences): the generated
// many-influence rigs (scripts/testdata/make_influence_cases.py).
#include "dqskin/error.hpp"
#include "dqskin/load.hpp"
#include "dqskin/skinning.hpp"

#include <gtest/gtest.h>

#include <string>

namespace dqskin {
namespace {

std::string influence_case(const std::string& name) { return std::string(DQSKIN_INFLUENCE_CASES_DIR) + "/" + name; }

const Primitive& skinned_primitive(const Asset& asset) { return asset.meshes.at(0).primitives.at(0); }

TEST(InfluenceSets, EverySetIsRead) {
  for (const auto& [file, sets] : {std::pair{"twelve_influences.gltf", 3}, std::pair{"twenty_influences.gltf", 5}}) {
    const Asset asset = load_asset(influence_case(file));
    const Primitive& prim = skinned_primitive(asset);
    ASSERT_EQ(prim.influences, 4 * sets) << file;
    // Every slot has weight: the last set is read, not left at zero.
    for (size_t v = 0; v < prim.vertex_count(); ++v)
      for (size_t k = 0; k < size_t(prim.influences); ++k) {
        ASSERT_GT(prim.weights[v * size_t(prim.influences) + k], 0.0f) << file << " vertex " << v << " slot " << k;
        ASSERT_EQ(prim.joints[v * size_t(prim.influences) + k], k) << file << " vertex " << v << " slot " << k;
      }
    EXPECT_TRUE(weight_warnings(asset).empty()) << file << ": the weights sum to 1 within float rounding";
  }
}

// --max-influences 4 makes of the 20-influence rig exactly what the generator's top-4 file holds: the 4
// largest weights of each vertex (ties to the lower joint), in that order, renormalized in double and
// stored as float. So a bake with the flag and a bake of the cut file are one and the same.
TEST(MaxInfluences, KeepsTheLargestInOrderAndRenormalizes) {
  LoadOptions options;
  options.max_influences = 4;
  const Asset cut = load_asset(influence_case("twenty_influences.gltf"), options);
  const Asset top4 = load_asset(influence_case("twenty_influences_top4.gltf"));
  const Primitive& a = skinned_primitive(cut);
  const Primitive& b = skinned_primitive(top4);
  ASSERT_EQ(a.influences, 4);
  ASSERT_EQ(b.influences, 4);
  EXPECT_EQ(a.joints, b.joints);
  EXPECT_EQ(a.weights, b.weights);
  EXPECT_TRUE(weight_warnings(cut).empty());
}

TEST(MaxInfluences, SlotsAreTheFewestSetsThatHoldTheKeptOnes) {
  for (const auto& [keep, slots] : {std::pair{1, 4}, std::pair{5, 8}, std::pair{8, 8}, std::pair{9, 12}, std::pair{13, 16}}) {
    LoadOptions options;
    options.max_influences = keep;
    const Asset asset = load_asset(influence_case("twenty_influences.gltf"), options);
    const Primitive& p = skinned_primitive(asset);
    ASSERT_EQ(p.influences, slots) << keep;
    for (size_t v = 0; v < p.vertex_count(); ++v) {
      double sum = 0;
      int with_weight = 0;
      for (size_t k = 0; k < size_t(slots); ++k) {
        const float w = p.weights[v * size_t(slots) + k];
        sum += double(w);
        with_weight += w > 0 ? 1 : 0;
        if (k > 0) {
          EXPECT_LE(w, p.weights[v * size_t(slots) + k - 1]) << "kept ones come largest first";
        }
      }
      EXPECT_EQ(with_weight, keep) << "vertex " << v;
      EXPECT_NEAR(sum, 1.0, 1e-6) << "vertex " << v;
    }
  }
}

// A limit the file does not exceed changes nothing, byte for byte: the option costs nothing where it
// drops nothing.
TEST(MaxInfluences, ALimitNotExceededLeavesTheAssetAsItWas) {
  const Asset plain = load_asset(influence_case("twelve_influences.gltf"));
  for (int keep : {12, 20, kMaxInfluences}) {
    LoadOptions options;
    options.max_influences = keep;
    const Asset same = load_asset(influence_case("twelve_influences.gltf"), options);
    EXPECT_EQ(skinned_primitive(same).influences, skinned_primitive(plain).influences) << keep;
    EXPECT_EQ(skinned_primitive(same).joints, skinned_primitive(plain).joints) << keep;
    EXPECT_EQ(skinned_primitive(same).weights, skinned_primitive(plain).weights) << keep;
  }
}

}  // namespace
}  // namespace dqskin
