// `dqskin optimize` on the bundled rigs: the budget holds on the written file as an independent deformation
// measures it, keys and bytes go, nothing else of the file changes, and bad input writes nothing.
#include "dqskin/optimize.hpp"

#include "dqskin/animation.hpp"
#include "dqskin/error.hpp"
#include "dqskin/load.hpp"
#include "dqskin/skinning.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string rig(const std::string& name) { return std::string(DQSKIN_TESTDATA_DIR) + "/" + name; }

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("dqskin_optimize_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The largest distance between the two files' deformed vertices, deformed here by the CPU reference at every
// key time of either file and every midpoint, clip by clip: an independent measure of the output.
double worst_distance(const std::string& a_path, const std::string& b_path, BlendMode mode) {
  const Asset a = load_asset(a_path), b = load_asset(b_path);
  EXPECT_EQ(a.clips.size(), b.clips.size());
  const auto ia = mesh_instances(a, choose_scene(a, -1)), ib = mesh_instances(b, choose_scene(b, -1));
  double worst = 0;
  for (size_t c = 0; c < a.clips.size() && c < b.clips.size(); ++c) {
    std::set<double> keys;
    for (const Clip* clip : {&a.clips[c], &b.clips[c]})
      for (const Channel& ch : clip->channels) keys.insert(ch.times.begin(), ch.times.end());
    std::vector<double> times(keys.begin(), keys.end());
    for (size_t i = 1, n = times.size(); i < n; ++i) times.push_back((times[i - 1] + times[i]) / 2);
    for (double t : times) {
      const DeformedFrame fa = deform_frame(a, ia, sample_pose(a, &a.clips[c], t), mode);
      const DeformedFrame fb = deform_frame(b, ib, sample_pose(b, &b.clips[c], t), mode);
      EXPECT_EQ(fa.primitives.size(), fb.primitives.size());
      for (size_t p = 0; p < fa.primitives.size() && p < fb.primitives.size(); ++p)
        for (size_t v = 0; v < fa.primitives[p].positions.size(); ++v)
          worst = std::max(worst, glm::length(fa.primitives[p].positions[v] - fb.primitives[p].positions[v]));
    }
  }
  return worst;
}

OptimizeOptions budget(double length, BlendMode mode = BlendMode::kLbs) {
  OptimizeOptions o;
  o.max_error = length;
  o.mode = mode;
  return o;
}

class OptimizeRigs : public ::testing::TestWithParam<const char*> {};

TEST_P(OptimizeRigs, TheBudgetHoldsOnTheWrittenFileAndKeysGo) {
  const std::string input = rig(GetParam());
  const fs::path output = scratch(std::string(GetParam()) + ".glb");
  for (BlendMode mode : {BlendMode::kLbs, BlendMode::kDqs}) {
    OptimizeOptions o = budget(0, mode);
    o.max_error_percent = 1;  // of the rest pose's diagonal
    const OptimizeSummary s = optimize(input, output.string(), o);
    ASSERT_GT(s.budget, 0);
    EXPECT_NEAR(s.budget, s.diagonal / 100, 1e-12);
    size_t before = 0, after = 0;
    for (const ClipOptimization& c : s.clips) {
      EXPECT_LE(c.max_error, s.budget) << c.name;
      EXPECT_LE(c.p99_error, c.max_error) << c.name;
      before += c.keys_before;
      after += c.keys_after;
    }
    EXPECT_LT(after, before) << "a 1% budget removes keys of " << GetParam();
    EXPECT_LT(s.animation_bytes_after, s.animation_bytes_before);
    // Measured again here, independently of the optimizer's own measure.
    EXPECT_LE(worst_distance(input, output.string(), mode), s.budget * (1 + 1e-9)) << GetParam();
  }
}

INSTANTIATE_TEST_SUITE_P(Bundled, OptimizeRigs,
                         ::testing::Values("twisted_cylinder.gltf", "bending_arm.gltf", "walk_run_legs.gltf",
                                           "morph_skin.gltf", "two_skins.gltf"),
                         [](const ::testing::TestParamInfo<const char*>& param) {
                           const std::string name = param.param;
                           return name.substr(0, name.find('.'));
                         });

TEST(Optimize, ABudgetOfZeroChangesNoVertex) {
  const fs::path output = scratch("zero.glb");
  const OptimizeSummary s = optimize(rig("bending_arm.gltf"), output.string(), budget(0));
  for (const ClipOptimization& c : s.clips) EXPECT_EQ(c.max_error, 0) << c.name;
  EXPECT_EQ(worst_distance(rig("bending_arm.gltf"), output.string(), BlendMode::kLbs), 0);
}

// The case per-channel tolerances get wrong (a root at scale 200 makes a local 0.1° worth 200 times more on
// the surface): the budget is in world space, through the whole hierarchy.
TEST(Optimize, ARootScaledUpKeepsTheBudgetInWorldSpace) {
  json doc = json::parse(read_file(rig("bending_arm.gltf")));
  const json& scene = doc["scenes"][doc.value("scene", size_t(0))];
  for (const json& root : scene["nodes"]) doc["nodes"][root.get<size_t>()]["scale"] = {200.0, 200.0, 200.0};
  const fs::path scaled = scratch("scaled_arm.gltf"), output = scratch("scaled_arm.glb");
  std::ofstream(scaled) << doc.dump();
  const Asset asset = load_asset(scaled.string());
  const OptimizeSummary s = optimize(scaled.string(), output.string(), budget(0.01));
  EXPECT_GT(s.diagonal, 100) << "the scale reaches the surface";
  for (const ClipOptimization& c : s.clips) EXPECT_LE(c.max_error, 0.01) << c.name;
  EXPECT_LE(worst_distance(scaled.string(), output.string(), BlendMode::kLbs), 0.01 * (1 + 1e-9));
}

TEST(Optimize, MeshesSkinsAndRestTransformsStay) {
  const fs::path output = scratch("kept.glb");
  optimize(rig("walk_run_legs.gltf"), output.string(), budget(0.05));
  const Asset a = load_asset(rig("walk_run_legs.gltf")), b = load_asset(output.string());
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (size_t n = 0; n < a.nodes.size(); ++n) {
    EXPECT_EQ(a.nodes[n].local.translation, b.nodes[n].local.translation);
    EXPECT_EQ(a.nodes[n].local.rotation, b.nodes[n].local.rotation);
    EXPECT_EQ(a.nodes[n].local.scale, b.nodes[n].local.scale);
  }
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t m = 0; m < a.meshes.size(); ++m)
    for (size_t p = 0; p < a.meshes[m].primitives.size(); ++p) {
      EXPECT_EQ(a.meshes[m].primitives[p].positions, b.meshes[m].primitives[p].positions);
      EXPECT_EQ(a.meshes[m].primitives[p].weights, b.meshes[m].primitives[p].weights);
      EXPECT_EQ(a.meshes[m].primitives[p].joints, b.meshes[m].primitives[p].joints);
    }
  ASSERT_EQ(a.skins.size(), b.skins.size());
  for (size_t s = 0; s < a.skins.size(); ++s) EXPECT_EQ(a.skins[s].inverse_bind, b.skins[s].inverse_bind);
  ASSERT_EQ(a.clips.size(), b.clips.size());
  for (size_t c = 0; c < a.clips.size(); ++c) {
    EXPECT_EQ(a.clips[c].name, b.clips[c].name);
    EXPECT_EQ(a.clips[c].last_key, b.clips[c].last_key) << "a clip keeps its length";
  }
}

// The JSON chunk of a .glb (§4.4: 12-byte header, then the chunk's length and type, then the JSON).
json glb_json(const fs::path& path) {
  const std::string bytes = read_file(path);
  uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return json::parse(bytes.substr(20, length));
}

// Float rotations go out as normalized shorts (glTF 2.0 §3.11), within the budget; --keep-float keeps floats.
TEST(Optimize, RotationsAreStoredAsNormalizedShorts) {
  for (bool quantize : {true, false}) {
    const fs::path output = scratch(quantize ? "shorts.glb" : "floats.glb");
    OptimizeOptions o = budget(0.02);
    o.quantize_rotations = quantize;
    const OptimizeSummary s = optimize(rig("walk_run_legs.gltf"), output.string(), o);
    for (const ClipOptimization& c : s.clips) EXPECT_LE(c.max_error, 0.02) << c.name;
    const json doc = glb_json(output);
    size_t rotations = 0;
    for (const json& animation : doc["animations"])
      for (const json& channel : animation["channels"]) {
        if (channel["target"]["path"] != "rotation") continue;
        const json& accessor = doc["accessors"][animation["samplers"][channel["sampler"].get<size_t>()]["output"].get<size_t>()];
        EXPECT_EQ(accessor["componentType"], quantize ? 5122 : 5126);
        EXPECT_EQ(accessor.value("normalized", false), quantize);
        ++rotations;
      }
    EXPECT_GT(rotations, 0u);
    EXPECT_LE(worst_distance(rig("walk_run_legs.gltf"), output.string(), BlendMode::kLbs), 0.02 * (1 + 1e-9));
  }
}

// The component type of every output accessor of channels with `path`, over all animations.
std::multiset<int> output_types(const json& doc, const std::string& path) {
  std::multiset<int> types;
  for (const json& animation : doc["animations"])
    for (const json& channel : animation["channels"]) {
      if (channel["target"]["path"] != path) continue;
      const json& accessor = doc["accessors"][animation["samplers"][channel["sampler"].get<size_t>()]["output"].get<size_t>()];
      types.insert(accessor["componentType"].get<int>() * (accessor.value("normalized", false) ? 1 : -1));
    }
  return types;
}

// Morph weights in [0, 1] go out as normalized unsigned bytes or shorts (glTF 2.0 §3.11 allows them for
// weights), whichever is the smallest within the budget; --keep-float keeps floats.
TEST(Optimize, MorphWeightsAreStoredAsNormalizedIntegers) {
  for (bool quantize : {true, false}) {
    const fs::path output = scratch(quantize ? "weights_quantized.glb" : "weights_float.glb");
    OptimizeOptions o = budget(0);
    o.max_error_percent = 1;
    o.quantize_weights = o.quantize_rotations = quantize;
    const OptimizeSummary s = optimize(rig("morph_skin.gltf"), output.string(), o);
    const std::multiset<int> types = output_types(glb_json(output), "weights");
    ASSERT_EQ(types.size(), 1u);
    if (quantize) EXPECT_TRUE(*types.begin() == 5121 || *types.begin() == 5123) << *types.begin();
    else EXPECT_EQ(*types.begin(), -5126);
    EXPECT_LE(worst_distance(rig("morph_skin.gltf"), output.string(), BlendMode::kLbs), s.budget * (1 + 1e-9));
  }
}

// interpolation_modes.gltf's CUBICSPLINE clip: a channel becomes LINEAR where that is smaller, STEP stays
// STEP, and the surface stays within the budget (between keys too: the linear keys are checked along the
// curve, the union of both files' keys and midpoints here).
TEST(Optimize, CubicSplineBecomesLinearWhereSmaller) {
  for (bool convert : {true, false}) {
    const fs::path output = scratch(convert ? "cubic_linear.glb" : "cubic_kept.glb");
    OptimizeOptions o = budget(0);
    o.max_error_percent = 1;
    o.convert_interpolation = convert;
    const OptimizeSummary s = optimize(rig("interpolation_modes.gltf"), output.string(), o);
    const json doc = glb_json(output);
    std::multiset<std::string> modes;
    for (const json& animation : doc["animations"])
      for (const json& sampler : animation["samplers"]) modes.insert(sampler.value("interpolation", std::string("LINEAR")));
    // Of the two 3-key channels, the linear equivalent of one takes fewer bytes; the other stays cubic.
    if (convert) EXPECT_LT(modes.count("CUBICSPLINE"), 2u);
    else EXPECT_EQ(modes.count("CUBICSPLINE"), 2u);
    EXPECT_EQ(modes.count("STEP"), 1u);
    EXPECT_LT(s.animation_bytes_after, s.animation_bytes_before);
    EXPECT_LE(worst_distance(rig("interpolation_modes.gltf"), output.string(), BlendMode::kLbs), s.budget * (1 + 1e-9));
  }
}

TEST(Optimize, TheSameInputAndFlagsWriteTheSameBytes) {
  const fs::path one = scratch("one.glb"), two = scratch("two.glb");
  optimize(rig("walk_run_legs.gltf"), one.string(), budget(0.02));
  optimize(rig("walk_run_legs.gltf"), two.string(), budget(0.02));
  EXPECT_EQ(read_file(one), read_file(two));
}

TEST(Optimize, BadBudgetsAndInputsWriteNothing) {
  const fs::path output = scratch("bad.glb");
  fs::remove(output);
  EXPECT_THROW(optimize(rig("bending_arm.gltf"), output.string(), budget(-1)), InputError);
  EXPECT_THROW(optimize(rig("bending_arm.gltf"), output.string(), budget(std::nan(""))), InputError);
  EXPECT_THROW(optimize(rig("bending_arm.gltf"), output.string(), budget(std::numeric_limits<double>::infinity())), InputError);
  json doc = json::parse(read_file(rig("bending_arm.gltf")));
  doc.erase("animations");
  const fs::path still = scratch("still.gltf");
  std::ofstream(still) << doc.dump();
  try {
    optimize(still.string(), output.string(), budget(0.01));
    ADD_FAILURE() << "a file without animation was optimized";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("has no animation"), std::string::npos) << e.what();
  }
  EXPECT_THROW(optimize(rig("bending_arm.gltf"), "/nonexistent-folder/out.glb", budget(0.01)), OutputError);
  EXPECT_FALSE(fs::exists(output));
}

// The shared sample models: every one optimized at 0.1 % of its diagonal stays within it.
TEST(OptimizeShared, EveryModelKeepsItsBudget) {
  const fs::path shared = DQSKIN_SHARED_TESTDATA_DIR;
  if (!fs::exists(shared)) GTEST_SKIP() << "shared test data not found at " << shared;
  for (const char* model : {"CesiumMan/CesiumMan.glb", "RiggedSimple/RiggedSimple.glb", "Fox/Fox.glb"}) {
    const fs::path input = shared / model;
    if (!fs::exists(input)) {
      ADD_FAILURE() << input << " is missing from the shared test data";
      continue;
    }
    const fs::path output = scratch(input.filename().string());
    OptimizeOptions o = budget(0);
    o.max_error_percent = 0.1;
    const OptimizeSummary s = optimize(input.string(), output.string(), o);
    for (const ClipOptimization& c : s.clips) EXPECT_LE(c.max_error, s.budget) << model << " " << c.name;
    EXPECT_LE(s.animation_bytes_after, s.animation_bytes_before) << model;
  }
}

// RiggedFigure's constant channels equal its rest values in float but not in double: at a budget of 0 the
// float deformer of the search sees no error, the double one of the written file 5e-6. The clip is then
// written as it was, with a note, and the budget holds.
TEST(OptimizeShared, AReductionOverTheBudgetAsWrittenIsUndone) {
  const fs::path input = fs::path(DQSKIN_SHARED_TESTDATA_DIR) / "RiggedFigure/RiggedFigure.glb";
  if (!fs::exists(input)) GTEST_SKIP() << input << " not found (shared test data)";
  const fs::path output = scratch("RiggedFigure0.glb");
  const OptimizeSummary s = optimize(input.string(), output.string(), budget(0));
  ASSERT_EQ(s.clips.size(), 1u);
  EXPECT_EQ(s.clips[0].max_error, 0);
  EXPECT_EQ(s.clips[0].keys_after, s.clips[0].keys_before);
  ASSERT_FALSE(s.notes.empty());
  EXPECT_NE(s.notes.front().find("on the written file, over the budget"), std::string::npos) << s.notes.front();
  EXPECT_EQ(worst_distance(input.string(), output.string(), BlendMode::kLbs), 0);
}

}  // namespace
}  // namespace dqskin
