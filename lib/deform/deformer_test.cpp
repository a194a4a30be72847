// The Deformer interface: the backend names, the one rule for where a deformation runs, and every
// implementation handing out every requested time once, in order, with the same vertices (float paths
// within 1e-4 scene units of the double reference; gpu_deformer_test.cpp and fast_cpu_deformer_test.cpp
// hold every rig and model to the tighter 1e-5 × the bounding-box diagonal).
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
  for (Backend b : {Backend::kAuto, Backend::kEgl, Backend::kOsMesa, Backend::kFastCpu, Backend::kCpu}) {
    Backend parsed = b == Backend::kCpu ? Backend::kAuto : Backend::kCpu;
    ASSERT_TRUE(parse_backend(to_string(b), parsed)) << to_string(b);
    EXPECT_EQ(parsed, b);
  }
  Backend untouched = Backend::kEgl;
  EXPECT_FALSE(parse_backend("vulkan", untouched));
  EXPECT_FALSE(parse_backend("CPU", untouched));
  EXPECT_EQ(untouched, Backend::kEgl);
  EXPECT_EQ(unknown_backend("vulkan"), "--backend 'vulkan' is not one of auto, egl, osmesa, fast-cpu, cpu");
}

TEST(Backend, DibAndCpuDeformOnTheReferenceFastCpuOnItselfEglAndOsmesaOnTheGpu) {
  EXPECT_FALSE(has_gpu_path(BlendMode::kDib));
  for (BlendMode m : {BlendMode::kLbs, BlendMode::kDqs}) {
    EXPECT_TRUE(has_gpu_path(m));
    EXPECT_EQ(deform_path(Backend::kCpu, m, nullptr), DeformPath::kReference);
    EXPECT_EQ(deform_path(Backend::kFastCpu, m, nullptr), DeformPath::kFastCpu);
    EXPECT_EQ(deform_path(Backend::kAuto, m, nullptr), DeformPath::kFastCpu) << "auto without a hardware GPU";
    for (Backend b : {Backend::kEgl, Backend::kOsMesa}) EXPECT_EQ(deform_path(b, m, nullptr), DeformPath::kGpu);
  }
  for (Backend b : {Backend::kAuto, Backend::kEgl, Backend::kOsMesa, Backend::kFastCpu, Backend::kCpu})
    EXPECT_EQ(deform_path(b, BlendMode::kDib, nullptr), DeformPath::kReference);
  EXPECT_EQ(describe(DeformPath::kGpu), "gpu");
  EXPECT_EQ(describe(DeformPath::kReference), "cpu-reference");
  EXPECT_EQ(describe(DeformPath::kFastCpu).rfind("fast-cpu (", 0), 0u);
}

// auto deforms on a context only when it is a hardware GPU's; a software rasterizer's (llvmpipe) is slower
// than the fast CPU deformer on the same cores.
TEST(Backend, AutoDeformsOnTheGpuOnlyWhenTheContextIsHardware) {
  const std::unique_ptr<GpuContext> context = testing_support::context_or_null(Backend::kAuto);
  if (!context) GTEST_SKIP() << "no OpenGL 4.3 context on this machine";
  const bool software = context->info().renderer.find("llvmpipe") != std::string::npos ||
                        context->info().renderer.find("softpipe") != std::string::npos;
  EXPECT_EQ(context->info().hardware, !software) << context->info().renderer;
  EXPECT_EQ(deform_path(Backend::kAuto, BlendMode::kDqs, context.get()),
            context->info().hardware ? DeformPath::kGpu : DeformPath::kFastCpu);
  EXPECT_EQ(deform_path(Backend::kEgl, BlendMode::kDqs, context.get()), DeformPath::kGpu);
  // The hardware question makes no software context.
  if (const std::unique_ptr<GpuContext> hardware = create_hardware_gpu_context()) {
    EXPECT_TRUE(hardware->info().hardware) << hardware->info().renderer;
  }
}

// With --backend cpu or fast-cpu a CPU deformer deforms, and render still draws: the context is made as
// auto makes it.
TEST(Backend, CpuDeformersAskForAContextAsAutoDoes) {
  std::string made;
  {
    const std::unique_ptr<GpuContext> automatic = testing_support::context_or_null(Backend::kAuto);
    if (!automatic) GTEST_SKIP() << "no OpenGL 4.3 context on this machine";
    made = automatic->info().backend;
  }
  EXPECT_EQ(create_gpu_context(Backend::kCpu)->info().backend, made);
  EXPECT_EQ(create_gpu_context(Backend::kFastCpu)->info().backend, made);
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

// Frame by frame, whatever the batching: the largest difference of positions.
float largest_position_difference(const std::vector<DeformedBatch>& a, const std::vector<DeformedBatch>& b, size_t frames) {
  auto position = [](const std::vector<DeformedBatch>& batches, size_t frame, size_t i) {
    for (const DeformedBatch& batch : batches)
      if (frame < batch.first_frame + batch.frame_count) {
        const DeformedBatch::Primitive& p = batch.primitives[0];
        return p.positions[(frame - batch.first_frame) * p.vertices * 3 + i];
      }
    return NAN;
  };
  const size_t values = a[0].primitives[0].vertices * 3;
  float worst = 0;
  for (size_t f = 0; f < frames; ++f)
    for (size_t i = 0; i < values; ++i) worst = std::max(worst, std::abs(position(a, f, i) - position(b, f, i)));
  return worst;
}

TEST_F(DeformerTest, TheReferenceAndTheFastCpuDeformerHandOutTheSameFramesInOrder) {
  DeformerOptions cpu;
  cpu.backend = Backend::kCpu;
  const std::vector<DeformedBatch> expected = run_all(*make_deformer(nullptr, asset_, instances_, cpu), asset_, times_);
  DeformerOptions fast;
  fast.backend = Backend::kFastCpu;
  const std::unique_ptr<Deformer> deformer = make_deformer(nullptr, asset_, instances_, fast);
  const std::vector<DeformedBatch> got = run_all(*deformer, asset_, times_);
  EXPECT_GT(deformer->stats().deform_seconds, 0.0);
  EXPECT_LT(largest_position_difference(got, expected, times_.size()), 1e-4f);
}

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
  gpu.backend = testing_support::backend_of(*context);
  gpu.gpu_memory = 4096;  // a few frames per batch: several batches
  const std::unique_ptr<Deformer> deformer = make_deformer(context.get(), asset_, instances_, gpu);
  const std::vector<DeformedBatch> got = run_all(*deformer, asset_, times_);
  EXPECT_GT(got.size(), 1u);
  EXPECT_LT(largest_position_difference(got, expected, times_.size()), 1e-4f)
      << "about 2.4e-5 of the rest pose's 4.24-unit diagonal";
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
  DeformerOptions o;
  o.backend = Backend::kEgl;
  EXPECT_THROW(make_deformer(nullptr, asset_, instances_, o), std::invalid_argument);
}

}  // namespace
}  // namespace dqskin
