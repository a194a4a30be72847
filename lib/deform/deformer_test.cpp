// The Deformer interface: the backend names, the one rule for dib, and both implementations handing out
// every requested time once, in order, with the same vertices (GPU within 1e-4 scene units, float against
// double; gpu_deformer_test.cpp holds every rig and model to the tighter 1e-5 × the bounding-box diagonal).
#include "dqskin/deformer.hpp"
#include "dqskin/error.hpp"
#include "dqskin/load.hpp"
#include "../test_support/gpu_context.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace dqskin {
namespace {

std::string rig(const char* name) { return std::string(DQSKIN_TESTDATA_DIR) + "/" + name; }

TEST(Backend, NamesRoundTripAndUnknownOnesAreRefusedInWords) {
  for (Backend b : {Backend::kAuto, Backend::kEgl, Backend::kOsMesa, Backend::kCpu}) {
    Backend parsed = b == Backend::kCpu ? Backend::kAuto : Backend::kCpu;
    ASSERT_TRUE(parse_backend(to_string(b), parsed)) << to_string(b);
    EXPECT_EQ(parsed, b);
  }
  Backend untouched = Backend::kEgl;
  EXPECT_FALSE(parse_backend("vulkan", untouched));
  EXPECT_FALSE(parse_backend("CPU", untouched));
  EXPECT_EQ(untouched, Backend::kEgl);
  EXPECT_EQ(unknown_backend("vulkan"), "--backend 'vulkan' is not one of auto, egl, osmesa, cpu");
}

TEST(Backend, DibAndCpuDeformOnTheReferenceEverythingElseOnTheGpu) {
  EXPECT_FALSE(has_gpu_path(BlendMode::kDib));
  for (BlendMode m : {BlendMode::kLbs, BlendMode::kDqs}) {
    EXPECT_TRUE(has_gpu_path(m));
    EXPECT_TRUE(deforms_on_cpu(Backend::kCpu, m));
    for (Backend b : {Backend::kAuto, Backend::kEgl, Backend::kOsMesa}) EXPECT_FALSE(deforms_on_cpu(b, m));
  }
  for (Backend b : {Backend::kAuto, Backend::kEgl, Backend::kOsMesa, Backend::kCpu})
    EXPECT_TRUE(deforms_on_cpu(b, BlendMode::kDib));
}

// With --backend cpu the reference deforms, and render still draws: the context is made as auto makes it.
TEST(Backend, CpuAsksForAContextAsAutoDoes) {
  std::string made;
  {
    const std::unique_ptr<GpuContext> automatic = testing_support::context_or_null(Backend::kAuto);
    if (!automatic) GTEST_SKIP() << "no OpenGL 4.3 context on this machine";
    made = automatic->info().backend;
  }
  EXPECT_EQ(create_gpu_context(Backend::kCpu)->info().backend, made);
}

// Runs a deformer over 21 times and checks the batches: in order, contiguous, each time once.
std::vector<DeformedBatch> run_all(Deformer& deformer, const Asset& asset, const std::vector<double>& times) {
  std::vector<DeformedBatch> batches;
  deformer.run(&asset.clips[0], times, [&](const DeformedBatch& b) { batches.push_back(b); });
  size_t next = 0;
  for (const DeformedBatch& b : batches) {
    EXPECT_EQ(b.first_frame, next);
    EXPECT_GT(b.frame_count, 0u);
    next += b.frame_count;
  }
  EXPECT_EQ(next, times.size());
  return batches;
}

class DeformerTest : public testing::Test {
protected:
  const Asset asset_ = load_asset(rig("twisted_cylinder.gltf"));
  const std::vector<MeshInstance> instances_ = mesh_instances(asset_, choose_scene(asset_, -1));
  std::vector<double> times_;
  void SetUp() override {
    for (int i = 0; i <= 20; ++i) times_.push_back(asset_.clips[0].last_key * i / 20.0);
  }
};

TEST_F(DeformerTest, TheReferenceAndTheGpuHandOutTheSameFramesInOrder) {
  DeformerOptions cpu;
  cpu.backend = Backend::kCpu;
  const std::unique_ptr<Deformer> reference = make_deformer(nullptr, asset_, instances_, cpu);
  const std::vector<DeformedBatch> expected = run_all(*reference, asset_, times_);
  EXPECT_GT(expected.size(), 1u) << "21 frames come in several batches";
  EXPECT_GT(reference->stats().deform_seconds, 0.0);

  const std::unique_ptr<GpuContext> context = testing_support::context_or_null();
  if (!context) GTEST_SKIP() << "no OpenGL 4.3 context on this machine";
  DeformerOptions gpu;
  gpu.gpu_memory = 4096;  // a few frames per batch: several batches
  const std::unique_ptr<Deformer> deformer = make_deformer(context.get(), asset_, instances_, gpu);
  const std::vector<DeformedBatch> got = run_all(*deformer, asset_, times_);
  EXPECT_GT(got.size(), 1u);

  // Frame by frame, whatever the batching.
  auto position = [](const std::vector<DeformedBatch>& batches, size_t frame, size_t i) {
    for (const DeformedBatch& b : batches)
      if (frame < b.first_frame + b.frame_count) {
        const DeformedBatch::Primitive& p = b.primitives[0];
        return p.positions[(frame - b.first_frame) * p.vertices * 3 + i];
      }
    return NAN;
  };
  const size_t values = expected[0].primitives[0].vertices * 3;
  float worst = 0;
  for (size_t f = 0; f < times_.size(); ++f)
    for (size_t i = 0; i < values; ++i) worst = std::max(worst, std::abs(position(got, f, i) - position(expected, f, i)));
  EXPECT_LT(worst, 1e-4f) << "about 2.4e-5 of the rest pose's 4.24-unit diagonal";
}

TEST_F(DeformerTest, TheReferenceCallsBeforeBatchSoThatARunCanBeStopped) {
  DeformerOptions o;
  o.backend = Backend::kCpu;
  int calls = 0;
  o.before_batch = [&] {
    if (++calls == 2) throw std::runtime_error("stop");
  };
  const std::unique_ptr<Deformer> deformer = make_deformer(nullptr, asset_, instances_, o);
  size_t batches = 0;
  EXPECT_THROW(deformer->run(&asset_.clips[0], times_, [&](const DeformedBatch&) { ++batches; }), std::runtime_error);
  EXPECT_EQ(batches, 1u);
}

TEST_F(DeformerTest, TheGpuPathWithoutAContextIsAProgrammingError) {
  EXPECT_THROW(make_deformer(nullptr, asset_, instances_, DeformerOptions{}), std::invalid_argument);
}

}  // namespace
}  // namespace dqskin
