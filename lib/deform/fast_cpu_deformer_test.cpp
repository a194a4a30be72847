// The fast CPU deformer against the double-precision reference (the oracle) on every rig and shared model,
// lbs and dqs, in every kernel build this CPU runs, to test_support/deform_accuracy.hpp's tolerances (the
// GPU path's); and its bytes, which depend on neither the thread count nor the run.
#include "fast_cpu_deformer.hpp"

#include "dqskin/error.hpp"
#include "dqskin/load.hpp"
#include "../test_support/deform_accuracy.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using deform::KernelIsa;

using testing_support::accuracy_times;
using testing_support::clips_or_rest;

struct Case {
  std::string path;
  BlendMode mode;
  KernelIsa isa;
};

class FastCpuMatchesReference : public testing::TestWithParam<Case> {};

TEST_P(FastCpuMatchesReference, EveryFrameOfEveryClip) {
  const Case& c = GetParam();
  if (!fs::exists(c.path)) GTEST_SKIP() << "test data not found: " << c.path;
  if (!deform::runs_here(c.isa)) GTEST_SKIP() << "this CPU does not run the " << deform::to_string(c.isa) << " kernel";
  const Asset asset = load_asset(c.path);
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  DeformerOptions options;
  options.mode = c.mode;
  const std::unique_ptr<Deformer> fast = deform::make_fast_cpu_deformer(asset, instances, options, c.isa);

  testing_support::AccuracyMeter meter;
  for (const Clip* clip : clips_or_rest(asset)) {
    const std::vector<double> times = accuracy_times(clip, testing_support::kSweepFps);
    fast->run(clip, times, [&](const DeformedBatch& batch) {
      for (size_t f = 0; f < batch.frame_count; ++f)
        meter.add(asset, instances, c.mode, clip, times[batch.first_frame + f], batch, f);
    });
  }
  // One row of the accuracy table in docs/PERFORMANCE.md.
  std::cout << "  accuracy | " << fs::path(c.path).filename().string() << " | " << to_string(c.mode) << " | "
            << deform::to_string(c.isa) << " | " << meter.worst_position << " | " << meter.position_tolerance() << " | "
            << meter.worst_normal << " | " << meter.worst_tangent << " | " << meter.ill_conditioned << "\n";
  EXPECT_LE(meter.worst_position, meter.position_tolerance());
  EXPECT_LE(meter.worst_normal, 1e-4);
  EXPECT_LE(meter.worst_tangent, 1e-4);
}

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const std::string& path : testing_support::accuracy_model_paths())
    for (BlendMode mode : {BlendMode::kLbs, BlendMode::kDqs})
      for (KernelIsa isa : {KernelIsa::kBaseline, KernelIsa::kAvx2Fma}) out.push_back({path, mode, isa});
  return out;
}

INSTANTIATE_TEST_SUITE_P(All, FastCpuMatchesReference, testing::ValuesIn(cases()),
                         [](const testing::TestParamInfo<Case>& p) {
                           std::string name = fs::path(p.param.path).stem().string() + "_" + to_string(p.param.mode) +
                                              "_" + deform::to_string(p.param.isa);
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

// Every batch of every clip, concatenated: the bytes a run hands out.
std::vector<float> run_bytes(const Asset& asset, BlendMode mode, unsigned threads) {
  DeformerOptions options;
  options.mode = mode;
  options.threads = threads;
  const std::unique_ptr<Deformer> fast =
      deform::make_fast_cpu_deformer(asset, mesh_instances(asset, choose_scene(asset, -1)), options);
  std::vector<float> out;
  for (const Clip* clip : clips_or_rest(asset))
    fast->run(clip, accuracy_times(clip), [&](const DeformedBatch& batch) {
      for (const DeformedBatch::Primitive& p : batch.primitives)
        for (const std::vector<float>* a : {&p.positions, &p.normals, &p.tangents}) out.insert(out.end(), a->begin(), a->end());
    });
  return out;
}

bool same_bytes(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// 1 thread, 2, and more threads than this machine has cores give the same bytes, and so does a second run.
TEST(FastCpuDeformer, BytesDoNotDependOnTheThreadCountOrTheRun) {
  for (const char* rig : {"morph_skin", "eight_influences", "nonuniform_scale", "two_skins"}) {
    const Asset asset = load_asset(std::string(DQSKIN_TESTDATA_DIR) + "/" + rig + ".gltf");
    for (BlendMode mode : {BlendMode::kLbs, BlendMode::kDqs}) {
      const std::vector<float> one = run_bytes(asset, mode, 1);
      ASSERT_FALSE(one.empty()) << rig;
      EXPECT_TRUE(same_bytes(one, run_bytes(asset, mode, 2))) << rig << " " << to_string(mode);
      EXPECT_TRUE(same_bytes(one, run_bytes(asset, mode, 7))) << rig << " " << to_string(mode);
      EXPECT_TRUE(same_bytes(one, run_bytes(asset, mode, 1))) << rig << " " << to_string(mode);
    }
  }
  const std::string brainstem = std::string(DQSKIN_SHARED_TESTDATA_DIR) + "/BrainStem/BrainStem.glb";
  if (!fs::exists(brainstem)) GTEST_SKIP() << "test data not found: " << brainstem;
  const Asset asset = load_asset(brainstem);  // 59 instances of one skin, 34k vertices: many work items
  EXPECT_TRUE(same_bytes(run_bytes(asset, BlendMode::kDqs, 1), run_bytes(asset, BlendMode::kDqs, 5)));
}

TEST(FastCpuDeformer, BeforeBatchCanStopARunAndSinkErrorsReachTheCaller) {
  const Asset asset = load_asset(std::string(DQSKIN_TESTDATA_DIR) + "/bending_arm.gltf");
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  std::vector<double> times(200);
  for (size_t i = 0; i < times.size(); ++i) times[i] = asset.clips[0].last_key * double(i) / 199.0;

  DeformerOptions stopping;
  int calls = 0;
  stopping.before_batch = [&] {
    if (++calls == 1) throw std::runtime_error("stop");
  };
  size_t batches = 0;
  EXPECT_THROW(deform::make_fast_cpu_deformer(asset, instances, stopping)->run(&asset.clips[0], times,
                                                                                [&](const DeformedBatch&) { ++batches; }),
               std::runtime_error);
  EXPECT_EQ(batches, 0u);

  const std::unique_ptr<Deformer> fast = deform::make_fast_cpu_deformer(asset, instances, DeformerOptions{});
  EXPECT_THROW(fast->run(&asset.clips[0], times, [](const DeformedBatch&) { throw std::runtime_error("disk full"); }),
               std::runtime_error);
}

TEST(FastCpuDeformer, DibIsRefusedInWords) {
  const Asset asset = load_asset(std::string(DQSKIN_TESTDATA_DIR) + "/bending_arm.gltf");
  DeformerOptions options;
  options.mode = BlendMode::kDib;
  try {
    deform::make_fast_cpu_deformer(asset, mesh_instances(asset, -1), options);
    ADD_FAILURE() << "dib was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("dib"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dqskin
