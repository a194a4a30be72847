// The GPU path against the CPU reference (the oracle): every rig and shared model, both modes, both
// backends, every frame, to test_support/deform_accuracy.hpp's tolerances.
#include "dqskin/gpu_deform.hpp"
#include "dqskin/error.hpp"
#include "dqskin/load.hpp"
#include "../test_support/deform_accuracy.hpp"
#include "../test_support/gpu_context.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <thread>

namespace dqskin {
namespace {

namespace fs = std::filesystem;

using testing_support::context_or_null;

struct Case {
  std::string path;
  BlendMode mode;
  Backend backend;
};

class GpuMatchesCpu : public testing::TestWithParam<Case> {};

TEST_P(GpuMatchesCpu, EveryFrameOfEveryClip) {
  const Case& c = GetParam();
  if (!fs::exists(c.path)) GTEST_SKIP() << "test data not found: " << c.path;
  std::unique_ptr<GpuContext> ctx = context_or_null(c.backend);
  if (!ctx) GTEST_SKIP() << "no OpenGL 4.3 context with backend " << to_string(c.backend);

  const Asset asset = load_asset(c.path);
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  GpuDeformer gpu(*ctx, asset, instances, {c.mode, size_t(64) << 20});

  testing_support::AccuracyMeter meter;
  for (const Clip* clip : testing_support::clips_or_rest(asset)) {
    const std::vector<double> times = testing_support::accuracy_times(clip, testing_support::kSweepFps);
    gpu.run(clip, times, [&](const DeformedBatch& batch) {
      for (size_t f = 0; f < batch.frame_count; ++f)
        meter.add(asset, instances, c.mode, clip, times[batch.first_frame + f], batch, f);
    });
  }
  std::cout << "  " << fs::path(c.path).filename().string() << " " << to_string(c.mode) << " "
            << ctx->info().backend << ": max position error " << meter.worst_position << " (tolerance "
            << meter.position_tolerance() << "), max normal error " << meter.worst_normal << " ("
            << meter.ill_conditioned << " undefined normals skipped)\n";
  EXPECT_LE(meter.worst_position, meter.position_tolerance());
  EXPECT_LE(meter.worst_normal, 1e-4);
}

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const std::string& path : testing_support::accuracy_model_paths())
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

// Persistently mapped outputs and glGetBufferSubData read the same bytes, and a second run over reused
// batch buffers hands out the same bytes again.
TEST(GpuDeformer, MappedAndCopiedReadbackGiveTheSameBytes) {
  const std::unique_ptr<GpuContext> ctx = context_or_null();
  if (!ctx) GTEST_SKIP() << "no OpenGL 4.3 context";
  const Asset asset = load_asset(std::string(DQSKIN_TESTDATA_DIR) + "/morph_skin.gltf");
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  std::vector<double> times(37);
  for (size_t i = 0; i < times.size(); ++i) times[i] = asset.clips[0].last_key * double(i) / 36.0;
  auto bytes = [&](GpuDeformer& gpu) {
    std::vector<float> out;
    gpu.run(&asset.clips[0], times, [&](const DeformedBatch& batch) {
      for (const DeformedBatch::Primitive& p : batch.primitives)
        for (const std::vector<float>* a : {&p.positions, &p.normals, &p.tangents}) out.insert(out.end(), a->begin(), a->end());
    });
    return out;
  };
  GpuDeformOptions options{BlendMode::kDqs, 8192};  // a few frames per batch: more batches than buffers
  GpuDeformer mapped(*ctx, asset, instances, options);
  options.mapped_readback = false;
  GpuDeformer copied(*ctx, asset, instances, options);
  EXPECT_FALSE(copied.mapped_readback());
  if (ctx->info().version.rfind("4.3", 0) != 0) {
    EXPECT_TRUE(mapped.mapped_readback()) << ctx->info().version;
  }
  ASSERT_GT(times.size(), 3 * mapped.frames_per_batch());
  const std::vector<float> a = bytes(mapped), b = bytes(copied);
  ASSERT_FALSE(a.empty());
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
  const std::vector<float> again = bytes(mapped);
  EXPECT_EQ(std::memcmp(a.data(), again.data(), a.size() * sizeof(float)), 0);
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
