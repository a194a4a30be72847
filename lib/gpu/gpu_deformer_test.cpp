// The GPU path against the CPU reference (the oracle): every rig and shared model, both modes, both
// backends, every frame. Tolerances: positions 1e-5 × the model's bounding-box diagonal, normals 1e-4.
#include "dqskin/gpu_deform.hpp"
#include "dqskin/error.hpp"
#include "dqskin/load.hpp"
#include "../test_support/gpu_context.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <thread>

namespace dqskin {
namespace {

namespace fs = std::filesystem;

using testing_support::context_or_null;

// A deformed normal is only defined where the blended 3×3 does not collapse the surface: LBS of a
// 180° twist (the candy wrapper) maps a ring onto the axis, and there the normal's direction is rounding
// noise in both paths. True when |cof(A) n| ≥ 1e-3 · |A|² (Frobenius) for the vertex's blend A (the LBS
// matrix, or the blended S under dqs).
bool well_conditioned_normal(const Asset& asset, const std::vector<MeshInstance>& instances, size_t flat_primitive,
                             const std::vector<JointTransforms>& skins, size_t v, BlendMode mode) {
  size_t index = 0;
  for (const MeshInstance& inst : instances) {
    const Mesh& mesh = asset.meshes[size_t(inst.mesh)];
    if (flat_primitive >= index + mesh.primitives.size()) {
      index += mesh.primitives.size();
      continue;
    }
    const Primitive& prim = mesh.primitives[flat_primitive - index];
    if (inst.skin < 0) return true;  // a node's world matrix: invertible in practice
    const JointTransforms& jt = skins[size_t(inst.skin)];
    Mat3<double> a(0.0);
    double sum = 0;
    for (size_t k = 0; k < size_t(prim.influences); ++k) sum += double(prim.weights[v * size_t(prim.influences) + k]);
    if (sum == 0) return true;
    for (size_t k = 0; k < size_t(prim.influences); ++k) {
      const double w = double(prim.weights[v * size_t(prim.influences) + k]) / sum;
      const size_t j = prim.joints[v * size_t(prim.influences) + k];
      a += w * (mode == BlendMode::kLbs ? Mat3<double>(jt.matrices[j]) : jt.scale[j]);
    }
    const Mat3<double> cof(glm::cross(a[1], a[2]), glm::cross(a[2], a[0]), glm::cross(a[0], a[1]));
    const double scale2 = glm::dot(a[0], a[0]) + glm::dot(a[1], a[1]) + glm::dot(a[2], a[2]);  // |A|², as cof(A) is quadratic
    return glm::length(cof * glm::dvec3(prim.normals[v])) >= 1e-3 * scale2;
  }
  return true;
}

struct Case {
  std::string path;
  BlendMode mode;
  Backend backend;
};

std::vector<std::string> model_paths() {
  std::vector<std::string> out;
  for (const char* rig : {"twisted_cylinder", "bending_arm", "uniform_scale", "nonuniform_scale", "eight_influences",
                          "interpolation_modes", "morph_skin", "two_skins"})
    out.push_back(std::string(DQSKIN_TESTDATA_DIR) + "/" + rig + ".gltf");
  for (const char* model : {"RiggedSimple/RiggedSimple.glb", "RiggedFigure/RiggedFigure.glb", "CesiumMan/CesiumMan.glb",
                            "SimpleSkin/SimpleSkin.gltf", "Fox/Fox.glb", "BrainStem/BrainStem.glb",
                            "RecursiveSkeletons/RecursiveSkeletons.glb", "raylib_robot/robot.glb",
                            "raylib_greenman/greenman.glb", "InterpolationTest/InterpolationTest.glb",
                            "AnimatedMorphCube/AnimatedMorphCube.glb", "SimpleMorph/SimpleMorph.gltf"})
    out.push_back(std::string(DQSKIN_SHARED_TESTDATA_DIR) + "/" + model);
  return out;
}

class GpuMatchesCpu : public testing::TestWithParam<Case> {};

TEST_P(GpuMatchesCpu, EveryFrameOfEveryClip) {
  const Case& c = GetParam();
  if (!fs::exists(c.path)) GTEST_SKIP() << "test data not found: " << c.path;
  std::unique_ptr<GpuContext> ctx = context_or_null(c.backend);
  if (!ctx) GTEST_SKIP() << "no OpenGL 4.3 context with backend " << to_string(c.backend);

  const Asset asset = load_asset(c.path);
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  GpuDeformer gpu(*ctx, asset, instances, {c.mode, size_t(64) << 20});

  double worst_position = 0, worst_normal = 0;
  size_t ill_conditioned = 0;
  glm::dvec3 lo(1e300), hi(-1e300);  // extent of the animation, for the tolerance
  const std::vector<const Clip*> clips = [&] {
    std::vector<const Clip*> v;
    for (const Clip& clip : asset.clips) v.push_back(&clip);
    if (v.empty()) v.push_back(nullptr);
    return v;
  }();
  for (const Clip* clip : clips) {
    FrameSpec spec;
    spec.fps = 10;  // every frame at 10 fps: enough frames to cross every key interval of these clips
    const std::vector<double> times = clip ? frame_times(*clip, spec) : std::vector<double>{0.0};
    gpu.run(clip, times, [&](const DeformedBatch& batch) {
      for (size_t f = 0; f < batch.frame_count; ++f) {
        const Pose pose = sample_pose(asset, clip, times[batch.first_frame + f]);
        std::vector<JointTransforms> skins;
        for (const Skin& skin : asset.skins) skins.push_back(joint_transforms(skin, pose));
        const DeformedFrame cpu = deform_frame(asset, instances, pose, c.mode);
        ASSERT_EQ(cpu.primitives.size(), batch.primitives.size());
        for (size_t p = 0; p < cpu.primitives.size(); ++p) {
          const DeformedBatch::Primitive& g = batch.primitives[p];
          const DeformedPrimitive& r = cpu.primitives[p];
          for (size_t v = 0; v < g.vertices; ++v) {
            const size_t o = (f * g.vertices + v) * 3;
            const glm::dvec3 gp(g.positions[o], g.positions[o + 1], g.positions[o + 2]);
            worst_position = std::max(worst_position, glm::distance(gp, r.positions[v]));
            lo = glm::min(lo, r.positions[v]);
            hi = glm::max(hi, r.positions[v]);
            if (!r.normals.empty() && !well_conditioned_normal(asset, instances, p, skins, v, c.mode)) {
              ++ill_conditioned;
            } else if (!r.normals.empty()) {
              const glm::dvec3 gn(g.normals[o], g.normals[o + 1], g.normals[o + 2]);
              worst_normal = std::max(worst_normal, glm::distance(gn, r.normals[v]));
            }
          }
        }
      }
    });
  }
  const double position_tolerance = 1e-5 * glm::distance(lo, hi);
  std::cout << "  " << fs::path(c.path).filename().string() << " " << to_string(c.mode) << " "
            << ctx->info().backend << ": max position error " << worst_position << " (tolerance "
            << position_tolerance << "), max normal error " << worst_normal << " (" << ill_conditioned
            << " undefined normals skipped)\n";
  EXPECT_LE(worst_position, position_tolerance);
  EXPECT_LE(worst_normal, 1e-4);
}

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const std::string& path : model_paths())
    for (BlendMode mode : {BlendMode::kLbs, BlendMode::kDqs})
      for (Backend backend : {Backend::kEgl, Backend::kOsMesa}) out.push_back({path, mode, backend});
  return out;
}

INSTANTIATE_TEST_SUITE_P(All, GpuMatchesCpu, testing::ValuesIn(cases()), [](const testing::TestParamInfo<Case>& p) {
  std::string name = fs::path(p.param.path).stem().string() + "_" + to_string(p.param.mode) + "_" + to_string(p.param.backend);
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
});

TEST(GpuDeformer, TwoRunsAreByteIdentical) {
  const std::string path = std::string(DQSKIN_TESTDATA_DIR) + "/twisted_cylinder.gltf";
  std::unique_ptr<GpuContext> ctx = context_or_null(Backend::kAuto);
  if (!ctx) GTEST_SKIP() << "no OpenGL 4.3 context";
  const Asset asset = load_asset(path);
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  const std::vector<double> times = frame_times(asset.clips[0], FrameSpec{});
  std::vector<std::vector<float>> runs(2);
  for (auto& run : runs) {
    GpuDeformer gpu(*ctx, asset, instances, {});
    gpu.run(&asset.clips[0], times, [&](const DeformedBatch& b) {
      for (const auto& p : b.primitives) run.insert(run.end(), p.positions.begin(), p.positions.end());
    });
  }
  ASSERT_EQ(runs[0].size(), runs[1].size());
  EXPECT_EQ(std::memcmp(runs[0].data(), runs[1].data(), runs[0].size() * 4), 0);
}

TEST(GpuDeformer, SmallBudgetSplitsIntoBatchesWithTheSameResult) {
  const std::string path = std::string(DQSKIN_TESTDATA_DIR) + "/bending_arm.gltf";
  std::unique_ptr<GpuContext> ctx = context_or_null(Backend::kAuto);
  if (!ctx) GTEST_SKIP() << "no OpenGL 4.3 context";
  const Asset asset = load_asset(path);
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  const std::vector<double> times = frame_times(asset.clips[0], FrameSpec{});
  std::vector<float> whole, split;
  GpuDeformer big(*ctx, asset, instances, {});
  big.run(&asset.clips[0], times, [&](const DeformedBatch& b) { whole = b.primitives[0].positions; });
  const Primitive& prim = asset.meshes[0].primitives[0];
  const size_t frame_bytes = prim.vertex_count() * (12u + (prim.normals.empty() ? 0u : 12u) + (prim.tangents.empty() ? 0u : 16u));
  // Room for two batches of 3 frames in flight.
  GpuDeformer small(*ctx, asset, instances, {BlendMode::kDqs, 2 * 3 * frame_bytes});
  EXPECT_EQ(small.frames_per_batch(), 3u);
  size_t batches = 0;
  small.run(&asset.clips[0], times, [&](const DeformedBatch& b) {
    ++batches;
    EXPECT_EQ(b.first_frame, split.size() / (prim.vertex_count() * 3));
    split.insert(split.end(), b.primitives[0].positions.begin(), b.primitives[0].positions.end());
  });
  EXPECT_EQ(batches, (times.size() + 2) / 3);
  EXPECT_EQ(whole, split);
}

TEST(GpuDeformer, SinkRunsInOrderOnItsOwnThreadAndItsErrorsReachTheCaller) {
  std::unique_ptr<GpuContext> ctx = context_or_null(Backend::kAuto);
  if (!ctx) GTEST_SKIP() << "no OpenGL 4.3 context";
  const Asset asset = load_asset(std::string(DQSKIN_TESTDATA_DIR) + "/bending_arm.gltf");
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  const std::vector<double> times = frame_times(asset.clips[0], FrameSpec{});
  const Primitive& prim = asset.meshes[0].primitives[0];
  const size_t frame_bytes = prim.vertex_count() * (12u + (prim.normals.empty() ? 0u : 12u));
  GpuDeformer gpu(*ctx, asset, instances, {BlendMode::kDqs, 2 * 2 * frame_bytes});  // 2 frames per batch
  ASSERT_EQ(gpu.frames_per_batch(), 2u);

  std::vector<size_t> firsts;
  std::thread::id sink_thread;
  gpu.run(&asset.clips[0], times, [&](const DeformedBatch& b) {
    firsts.push_back(b.first_frame);
    sink_thread = std::this_thread::get_id();
  });
  ASSERT_EQ(firsts.size(), (times.size() + 1) / 2);
  for (size_t i = 0; i < firsts.size(); ++i) EXPECT_EQ(firsts[i], 2 * i);
  EXPECT_NE(sink_thread, std::this_thread::get_id());

  size_t calls = 0;
  EXPECT_THROW(gpu.run(&asset.clips[0], times,
                       [&](const DeformedBatch&) {
                         if (++calls == 2) throw std::runtime_error("disk full");
                       }),
               std::runtime_error);
  EXPECT_EQ(calls, 2u);  // nothing after the failing batch
}

TEST(GpuDeformer, DibIsRefusedOnTheGpu) {
  std::unique_ptr<GpuContext> ctx = context_or_null(Backend::kAuto);
  if (!ctx) GTEST_SKIP() << "no OpenGL 4.3 context";
  const Asset asset = load_asset(std::string(DQSKIN_TESTDATA_DIR) + "/bending_arm.gltf");
  EXPECT_THROW(GpuDeformer(*ctx, asset, mesh_instances(asset, 0), {BlendMode::kDib, 1 << 20}), InputError);
}

}  // namespace
}  // namespace dqskin
