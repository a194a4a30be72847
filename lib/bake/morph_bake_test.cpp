// The morph-target animation end to end through the library: animation.glb read back with dqskin's own
// loader and played by the CPU reference (the weights sampled from the file's animation, morph targets
// added to the mesh, the node's transform applied) against the source deformed at every baked frame;
// keyframe reduction, sparse targets, quantization, determinism, viewer-limit warnings and refusals.
#include "morph_bake.hpp"

#include "dqskin/bake.hpp"

#include "dqskin/animation.hpp"
#include "dqskin/error.hpp"
#include "dqskin/load.hpp"
#include "dqskin/skinning.hpp"
#include "../test_support/read_file.hpp"
#include "../test_support/scratch_dir.hpp"
#include "../test_support/test_models.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing_support::read_file;

const unsigned kMorph = unsigned(BakeFormat::kMorph);

// The model's path as the bake takes it.
std::string model_path(const std::string& name) { return testing_support::model_path(name).string(); }

// Every vertex of every drawn primitive, per time, as the CPU reference deforms `clip_name` of `asset`
// (world space; normals of the primitives whose source has them, else zero).
struct Played {
  std::vector<std::vector<glm::dvec3>> positions, normals;
};

Played play(const Asset& asset, const std::string& clip_name, const std::vector<double>& times) {
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  const Clip* clip = nullptr;
  for (const Clip& c : asset.clips)
    if (c.name == clip_name) clip = &c;
  Played out;
  for (double t : times) {
    const DeformedFrame frame = deform_frame(asset, instances, sample_pose(asset, clip, t), BlendMode::kDqs);
    std::vector<glm::dvec3> p, n;
    size_t k = 0;
    for (const MeshInstance& inst : instances)
      for (const Primitive& prim : asset.meshes[size_t(inst.mesh)].primitives) {
        const DeformedPrimitive& d = frame.primitives[k++];
        p.insert(p.end(), d.positions.begin(), d.positions.end());
        for (size_t v = 0; v < d.positions.size(); ++v)
          n.push_back(prim.normals_generated || d.normals.empty() ? glm::dvec3(0.0) : d.normals[v]);
      }
    out.positions.push_back(std::move(p));
    out.normals.push_back(std::move(n));
  }
  return out;
}

// The JSON chunk of a .glb (§4.4: it follows the 12-byte header and its own 8-byte chunk header).
json glb_json(const std::string& glb) {
  uint32_t length = 0;
  std::memcpy(&length, glb.data() + 12, 4);
  return json::parse(glb.substr(20, length));
}

class MorphBakeTest : public testing::Test {
protected:
  BakeOptions options(const fs::path& out, double fps = 10) const {
    BakeOptions o;
    o.plan.out_dir = out.string();
    o.formats = kMorph;
    o.backend = Backend::kCpu;  // the reference, as the test plays both files on it
    o.plan.frames.fps = fps;
    o.jobs = 2;
    return o;
  }

  const testing_support::ScratchDir scratch_{"morph_bake"};
  const fs::path root_ = scratch_.path();
};

// Bakes `input` with `o` and checks every clip's animation.glb at every baked frame; the manifest goes to
// `manifest`.
void check_morph_bake(const std::string& input, const BakeOptions& o, json& manifest) {
  const BakeReport report = bake({input}, o);
  ASSERT_FALSE(report.any_failed()) << report.inputs[0].error;
  const fs::path out = o.plan.out_dir;

  // Exactly the planned files are there.
  BakeOptions dry = o;
  dry.dry_run = true;
  std::vector<std::string> planned;
  for (const BakeOutput& p : bake({input}, dry).outputs) planned.push_back(p.path);
  std::vector<std::string> written;
  for (const BakeOutput& p : report.outputs) written.push_back(p.path);
  EXPECT_EQ(written, planned);

  manifest = json::parse(read_file(out / "manifest.json"));
  const Asset source = load_asset(input);
  const TextureOptions& t = o.textures;
  for (const json& clip : manifest["inputs"][0]["animations"]) {
    const std::string name = clip["name"].get<std::string>();
    SCOPED_TRACE("clip " + name);
    const std::vector<double> times = clip["frame_times"].get<std::vector<double>>();
    const json& m = clip["morph"];
    const size_t keys = m["keyframes"].get<size_t>();
    EXPECT_EQ(m["frames"].get<size_t>(), times.size());
    EXPECT_EQ(m["quantized"].get<bool>(), o.morph.quantize);
    const fs::path file = out / clip["folder"].get<std::string>() / "animation.glb";
    EXPECT_EQ(m["bytes"].get<uint64_t>(), fs::file_size(file));

    const json doc = glb_json(read_file(file));
    ASSERT_EQ(doc["meshes"].size(), 1u);
    for (const json& p : doc["meshes"][0]["primitives"]) EXPECT_EQ(p.value("targets", json::array()).size(), keys - 1);
    if (keys > 1) {
      EXPECT_EQ(doc["meshes"][0]["extras"]["targetNames"].size(), keys - 1);
      EXPECT_EQ(doc["animations"][0]["name"], name);
    }
    const bool quantized = doc.contains("extensionsRequired") &&
                           doc["extensionsRequired"].dump().find("KHR_mesh_quantization") != std::string::npos;
    EXPECT_EQ(quantized, o.morph.quantize);

    const Asset back = load_asset(file.string());
    ASSERT_EQ(back.clips.size(), keys > 1 ? 1u : 0u);
    const Played truth = play(source, name, times);
    const Played shown = play(back, name, times);
    ASSERT_EQ(shown.positions.size(), truth.positions.size());
    glm::dvec3 lo(1e300), hi(-1e300);
    double magnitude = 0, motion = 0;
    for (const auto& frame : truth.positions)
      for (size_t v = 0; v < frame.size(); ++v) {
        lo = glm::min(lo, frame[v]), hi = glm::max(hi, frame[v]);
        magnitude = std::max(magnitude, glm::length(frame[v]));
        motion = std::max(motion, glm::distance(frame[v], truth.positions[0][v]));
      }
    // The bake measured against float frames, this against the double reference: float rounding apart.
    const double tolerance = 1e-6 * (glm::distance(lo, hi) + magnitude);
    double worst = 0, worst_normal = 0;
    for (size_t f = 0; f < times.size(); ++f) {
      ASSERT_EQ(shown.positions[f].size(), truth.positions[f].size());
      for (size_t v = 0; v < truth.positions[f].size(); ++v) {
        worst = std::max(worst, glm::distance(shown.positions[f][v], truth.positions[f][v]));
        const glm::dvec3 a = shown.normals[f][v], b = truth.normals[f][v];
        if (b != glm::dvec3(0.0)) worst_normal = std::max(worst_normal, std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
      }
    }
    EXPECT_NEAR(worst, m["max_error"].get<double>(), tolerance);
    EXPECT_LE(glm::degrees(worst_normal), m["max_normal_degrees"].get<double>() + 1e-3);
    if (t.max_error > 0) {
      const double budget = t.max_error_relative ? t.max_error * glm::distance(lo, hi) : t.max_error;
      EXPECT_LE(m["max_error"].get<double>(), budget);
      EXPECT_LE(worst, budget + tolerance);
    } else {
      EXPECT_EQ(keys, times.size());
    }
    // The comparison can fail: a clip that moves, compared far more finely than it moves (a displacement of
    // the wrong sign would be off by twice the motion).
    if (name != "rest" && times.size() > 1) {
      EXPECT_GT(motion, 1000 * tolerance);
    }
  }
}

// The rigs and shared models, each as every frame in float, reduced under 0.5 % of the clip's diagonal,
// and quantized and reduced. With DQSKIN_MORPH_GLB_SAMPLE_DIR set the bakes go there, for the Khronos
// glTF-Validator (CTest's morph_glb_validator).
class MorphBakeModels : public MorphBakeTest, public testing::WithParamInterface<const char*> {};

TEST_P(MorphBakeModels, EveryBakedFrameDecodesWithinTheReportedError) {
  const std::string input = model_path(GetParam());
  if (!fs::exists(input)) GTEST_SKIP() << "shared test data not found: " << input;
  const char* sample_dir = std::getenv("DQSKIN_MORPH_GLB_SAMPLE_DIR");
  const fs::path base = sample_dir && *sample_dir ? fs::path(sample_dir) : root_;
  struct Variant {
    const char* name;
    bool quantize;
    double max_error;
  };
  for (const Variant& v : {Variant{"float", false, 0.0}, Variant{"reduced", false, 0.005}, Variant{"quantized", true, 0.005}}) {
    SCOPED_TRACE(v.name);
    BakeOptions o = options(base / (fs::path(input).stem().string() + "_" + v.name));
    o.morph.quantize = v.quantize;
    o.textures.max_error = v.max_error;
    o.textures.max_error_relative = true;
    if (sample_dir && *sample_dir) o.overwrite = Overwrite::kReplace;
    json manifest;
    check_morph_bake(input, o, manifest);
  }
}

INSTANTIATE_TEST_SUITE_P(Models, MorphBakeModels,
                         testing::Values("twisted_cylinder.gltf", "bending_arm.gltf", "two_skins.gltf",
                                         "textured_cylinder.gltf", "morph_skin.gltf", "interpolation_modes.gltf",
                                         "CesiumMan/CesiumMan.glb", "Fox/Fox.glb", "RiggedFigure/RiggedFigure.glb",
                                         "AnimatedMorphCube/AnimatedMorphCube.glb"),
                         testing_support::model_test_name);

TEST_F(MorphBakeTest, ReductionKeepsFewerFramesOfASmoothClipWithinTheBudget) {
  BakeOptions o = options(root_ / "reduced", 30);
  o.textures.max_error = 0.01;  // 1 % of the diagonal
  o.textures.max_error_relative = true;
  json manifest;
  ASSERT_NO_FATAL_FAILURE(check_morph_bake(model_path("twisted_cylinder.gltf"), o, manifest));
  const json& m = manifest["inputs"][0]["animations"][0]["morph"];
  EXPECT_EQ(m["frames"].get<size_t>(), 31u);
  EXPECT_LT(m["keyframes"].get<size_t>(), 31u / 2);
  EXPECT_GT(m["max_error"].get<double>(), 0.0);
  EXPECT_EQ(manifest["morph"]["max_error"].get<double>(), 0.01);
}

TEST_F(MorphBakeTest, TargetsOfAnArmWhoseUpperHalfStaysAreSparse) {
  // bending_arm: the vertices bound to the shoulder alone (x ≤ 1.5 of 4) never move.
  for (bool quantize : {false, true}) {
    SCOPED_TRACE(quantize ? "quantized" : "float");
    BakeOptions o = options(root_ / (quantize ? "q" : "f"));
    o.morph.quantize = quantize;
    json manifest;
    ASSERT_NO_FATAL_FAILURE(check_morph_bake(model_path("bending_arm.gltf"), o, manifest));
    const json doc = glb_json(read_file(root_ / (quantize ? "q" : "f") / "bending_arm/bend/animation.glb"));
    const json& accessors = doc["accessors"];
    size_t targets = 0;
    for (const json& target : doc["meshes"][0]["primitives"][0]["targets"]) {
      const json& a = accessors[target["POSITION"].get<size_t>()];
      ++targets;
      ASSERT_TRUE(a.contains("sparse")) << a.dump();
      EXPECT_FALSE(a.contains("bufferView"));
      EXPECT_LT(a["sparse"]["count"].get<size_t>(), a["count"].get<size_t>() * 3 / 4);
      EXPECT_GT(a["sparse"]["count"].get<size_t>(), 0u);
      EXPECT_EQ(a["componentType"].get<int>(), quantize ? 5122 : 5126);  // SHORT or FLOAT
    }
    EXPECT_EQ(targets, 10u);  // 11 frames at 10 fps over 1 s
    EXPECT_GE(manifest["inputs"][0]["animations"][0]["morph"]["sparse_accessors"].get<size_t>(), targets);
  }
}

TEST_F(MorphBakeTest, TwoBakesAreByteIdentical) {
  BakeOptions a = options(root_ / "a"), b = options(root_ / "b");
  for (BakeOptions* o : {&a, &b}) {
    o->morph.quantize = true;
    o->textures.max_error = 0.002;
    o->textures.max_error_relative = true;
    o->jobs = o == &a ? 1 : 3;
    ASSERT_FALSE(bake({model_path("textured_cylinder.gltf")}, *o).any_failed());
  }
  const std::string file = "textured_cylinder/twist/animation.glb";
  EXPECT_EQ(read_file(root_ / "a" / file), read_file(root_ / "b" / file));
  EXPECT_EQ(read_file(root_ / "a/manifest.json"), read_file(root_ / "b/manifest.json"));
}

TEST_F(MorphBakeTest, AQuantizationGridCoarserThanTheBudgetIsRefusedAndLeavesNothing) {
  BakeOptions o = options(root_ / "unmet");
  o.morph.quantize = true;
  o.textures.max_error = 1e-6;  // the grid of a 4-unit cylinder has steps of 1.2e-4
  const BakeReport r = bake({model_path("twisted_cylinder.gltf")}, o);
  ASSERT_TRUE(r.any_failed());
  EXPECT_NE(r.inputs[0].error.find("clip twist: --morph-quantize's grid (a step of "), std::string::npos) << r.inputs[0].error;
  EXPECT_FALSE(fs::exists(root_ / "unmet" / "twisted_cylinder"));
}

TEST_F(MorphBakeTest, ABudgetBelowWhatFloatsStoreIsRefusedAndLeavesNothing) {
  BakeOptions o = options(root_ / "float");
  o.textures.max_error = 1e-12;  // every frame a key, each still a float rounding away
  const BakeReport r = bake({model_path("twisted_cylinder.gltf")}, o);
  ASSERT_TRUE(r.any_failed());
  EXPECT_NE(r.inputs[0].error.find("clip twist: the morph targets decode with errors up to "), std::string::npos)
      << r.inputs[0].error;
  EXPECT_FALSE(fs::exists(root_ / "float" / "twisted_cylinder"));
}

TEST_F(MorphBakeTest, MoreTargetsThanWebGl2ViewersDrawIsAWarning) {
  const BakeReport r = bake({model_path("twisted_cylinder.gltf")}, options(root_ / "many", 300));  // 301 frames
  ASSERT_FALSE(r.any_failed()) << r.inputs[0].error;
  ASSERT_EQ(r.inputs[0].warnings.size(), 1u);
  EXPECT_EQ(r.inputs[0].warnings[0].find("clip twist: 300 morph targets; three.js"), 0u) << r.inputs[0].warnings[0];
  const BakeReport few = bake({model_path("twisted_cylinder.gltf")}, options(root_ / "few", 30));
  EXPECT_TRUE(few.inputs[0].warnings.empty());
}

TEST(MorphViewerWarnings, APrimitivePastTheTexelsWebGl2GuaranteesIsAWarning) {
  using bake_detail::morph_viewer_warnings;
  // 2048 × 2048 texels: as many vertices without normals, half as many with them.
  const size_t texels = size_t(2048) * 2048;
  EXPECT_TRUE(morph_viewer_warnings("clip c", 10, {{texels, false}, {texels / 2, true}}).empty());
  const std::vector<std::string> w = morph_viewer_warnings("clip c", 10, {{7, true}, {texels / 2 + 1, true}});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].find("clip c: primitive 1 has 2097153 vertices; three.js on WebGL2"), 0u) << w[0];
  EXPECT_EQ(morph_viewer_warnings("clip c", 201, {{texels + 1, false}}).size(), 2u);
}

TEST_F(MorphBakeTest, FrameTimesThatDoNotIncreaseAreRefused) {
  BakeOptions o = options(root_ / "times");
  o.plan.frames.times = {0.5, 0.25};
  const BakeReport r = bake({model_path("bending_arm.gltf")}, o);
  ASSERT_TRUE(r.any_failed());
  EXPECT_NE(r.inputs[0].error.find("clip bend: a morph-target animation needs increasing frame times"), std::string::npos)
      << r.inputs[0].error;
}

TEST_F(MorphBakeTest, QuantizeWithoutMorphIsAUsageError) {
  BakeOptions o = options(root_ / "x");
  o.formats = unsigned(BakeFormat::kPly);
  o.morph.quantize = true;
  EXPECT_THROW(bake({model_path("bending_arm.gltf")}, o), InputError);
}

TEST_F(MorphBakeTest, ParsesMorphAsAFormat) {
  EXPECT_EQ(parse_bake_formats("glb,morph"), unsigned(BakeFormat::kGlb) | kMorph);
}

}  // namespace
}  // namespace dqskin
