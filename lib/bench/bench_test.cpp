// dqskin bench's parts that need no GL context: the synthetic character it measures and the ratios it
// prints from its rows (the measurements themselves are timings; `dqskin bench --quick` runs them).
#include "dqskin/bench.hpp"

#include "measure.hpp"
#include "synthetic_asset.hpp"

#include "dqskin/animation.hpp"
#include "dqskin/skinning.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace dqskin {
namespace {

using bench_detail::make_synthetic_asset;

TEST(SyntheticAsset, HasTheVerticesJointsAndFourNormalizedInfluencesAsked) {
  const Asset asset = make_synthetic_asset(1000, 32, false);
  ASSERT_EQ(asset.meshes.size(), 1u);
  const Primitive& p = asset.meshes[0].primitives[0];
  EXPECT_EQ(p.vertex_count(), 1000u);
  ASSERT_EQ(asset.skins.size(), 1u);
  EXPECT_EQ(asset.skins[0].joints.size(), 32u);
  EXPECT_EQ(p.influences, 4);
  for (size_t v = 0; v < p.vertex_count(); ++v) {
    float sum = 0;
    for (size_t k = 0; k < 4; ++k) {
      EXPECT_LT(p.joints[4 * v + k], 32u);
      sum += p.weights[4 * v + k];
    }
    EXPECT_NEAR(sum, 1.0f, 1e-5f) << "vertex " << v;
  }
  ASSERT_EQ(asset.clips.size(), 1u);
  EXPECT_EQ(asset.clips[0].channels.size(), 32u);  // one rotation per joint
}

TEST(SyntheticAsset, WithScaleEveryJointAlsoScales) {
  const Asset asset = make_synthetic_asset(640, 8, true);
  ASSERT_EQ(asset.clips.size(), 1u);
  EXPECT_EQ(asset.clips[0].channels.size(), 16u);  // a rotation and a scale per joint
  // The CPU reference deforms it: the bench's rows all run on it.
  const Pose pose = sample_pose(asset, &asset.clips[0], 0.5);
  const auto frame = deform_frame(asset, mesh_instances(asset, 0), pose, BlendMode::kDqs, 1);
  ASSERT_EQ(frame.primitives.size(), 1u);
}

BenchMeasurement row(const char* mode, const char* path, size_t vertices, size_t threads, double rate) {
  BenchMeasurement m;
  m.mode = mode, m.path = path, m.vertices = vertices, m.threads = threads, m.vertex_frames_per_second = rate;
  return m;
}

TEST(BenchRatios, PutTheFastRowOnEveryCoreBesideTheBoundTheBestGpuRowAndLbs) {
  const std::vector<BenchMeasurement> rows = {
      row("lbs", "gpu", 100, 0, 50), row("lbs", "gpu", 100, 0, 80), row("lbs", "fast", 100, 1, 10),
      row("lbs", "fast", 100, 4, 40), row("lbs", "cpu", 100, 1, 1), row("lbs", "copy", 100, 4, 200),
      row("dqs", "gpu", 100, 0, 60), row("dqs", "fast", 100, 4, 20), row("dqs", "copy", 100, 4, 100),
      row("lbs", "fast", 1000, 4, 30), row("lbs", "copy", 1000, 4, 300), row("lbs", "gpu", 1000, 0, 15)};
  const std::vector<BenchRatios> r = bench_ratios(rows, 4);
  ASSERT_EQ(r.size(), 3u);  // per size and mode, in the order measured
  EXPECT_EQ(r[0].mode, "lbs");
  EXPECT_EQ(r[0].vertices, 100u);
  EXPECT_DOUBLE_EQ(r[0].fast, 40);  // the every-core row, not the 1-thread one
  EXPECT_DOUBLE_EQ(r[0].of_bound, 40.0 / 200);
  EXPECT_DOUBLE_EQ(r[0].over_gpu, 40.0 / 80);  // the best GPU row
  EXPECT_DOUBLE_EQ(r[0].over_lbs, 1);
  EXPECT_EQ(r[1].mode, "dqs");
  EXPECT_DOUBLE_EQ(r[1].of_bound, 20.0 / 100);
  EXPECT_DOUBLE_EQ(r[1].over_gpu, 20.0 / 60);
  EXPECT_DOUBLE_EQ(r[1].over_lbs, 40.0 / 20);  // dqs takes twice lbs's time per vertex-frame
  EXPECT_EQ(r[2].vertices, 1000u);
  EXPECT_DOUBLE_EQ(r[2].over_gpu, 2);
}

TEST(BenchRatios, AMissingRowDividesByZeroInsteadOfShowingAFigure) {
  const std::vector<BenchRatios> r = bench_ratios({row("dqs", "fast", 100, 2, 20)}, 2);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_TRUE(std::isinf(r[0].of_bound));  // no memcpy row
  EXPECT_EQ(r[0].over_lbs, 0);             // no lbs row: 0 / 20
}

TEST(BenchMemcpy, MeasuresTheBoundOnTheThreadsAsked) {
  const BenchMeasurement m = bench_detail::measure_memcpy(1000, 2, 4, 0.01);
  EXPECT_EQ(m.path, "copy");
  EXPECT_EQ(m.threads, 2u);
  EXPECT_EQ(m.frames_per_batch, 4u);
  EXPECT_GT(m.vertex_frames_per_second, 0);
}

}  // namespace
}  // namespace dqskin
