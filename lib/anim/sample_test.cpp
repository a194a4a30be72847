#include "dqskin/animation.hpp"
#include "dqskin/load.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace dqskin {
namespace {

Channel channel(TargetPath path, Interpolation interpolation, std::vector<float> times, std::vector<float> values) {
  Channel ch;
  ch.path = path;
  ch.interpolation = interpolation;
  ch.components = path == TargetPath::kRotation ? 4 : 3;
  ch.times = std::move(times);
  ch.values = std::move(values);
  return ch;
}

TEST(SampleChannel, LinearInterpolatesAndClampsOutsideTheKeys) {
  const Channel ch = channel(TargetPath::kTranslation, Interpolation::kLinear, {1, 3}, {0, 0, 0, 2, 4, 6});
  EXPECT_EQ(sample_channel(ch, 0.0), (std::vector<double>{0, 0, 0}));   // before the first key: the first value
  EXPECT_EQ(sample_channel(ch, 2.0), (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(sample_channel(ch, 9.0), (std::vector<double>{2, 4, 6}));   // after the last key: the last value
}

TEST(SampleChannel, StepHoldsTheEarlierKey) {
  const Channel ch = channel(TargetPath::kScale, Interpolation::kStep, {0, 1, 2}, {1, 1, 1, 2, 2, 2, 3, 3, 3});
  EXPECT_EQ(sample_channel(ch, 0.999)[0], 1.0);
  EXPECT_EQ(sample_channel(ch, 1.0)[0], 2.0);
  EXPECT_EQ(sample_channel(ch, 1.5)[0], 2.0);
  EXPECT_EQ(sample_channel(ch, 5.0)[0], 3.0);
}

TEST(SampleChannel, LinearRotationIsShortestPathSlerp) {
  // Keys 0° and 270° about z stored as q and a quaternion with negative dot: the short way is −90°.
  const float s = float(std::sin(M_PI * 0.75)), c = float(std::cos(M_PI * 0.75));
  const Channel ch = channel(TargetPath::kRotation, Interpolation::kLinear, {0, 1}, {0, 0, 0, 1, 0, 0, s, c});
  const std::vector<double> mid = sample_channel(ch, 0.5);
  // Halfway along −90° is −45°: (0, 0, −sin 22.5°, cos 22.5°).
  EXPECT_NEAR(mid[2], -std::sin(M_PI / 8), 1e-6);
  EXPECT_NEAR(mid[3], std::cos(M_PI / 8), 1e-6);
}

TEST(SampleChannel, CubicSplineReproducesACubic) {
  // p(t) = t³ − t on keys 0, 0.5, 2 with tangents p'(t) = 3t² − 1: Hermite interpolation is exact.
  auto p = [](double t) { return t * t * t - t; };
  auto dp = [](double t) { return 3 * t * t - 1; };
  std::vector<float> times = {0, 0.5f, 2}, values;
  for (float key : times) {
    const double t = double(key);
    for (double v : {dp(t), p(t), dp(t)}) values.insert(values.end(), {float(v), 0, 0});
  }
  const Channel ch = channel(TargetPath::kTranslation, Interpolation::kCubicSpline, times, values);
  for (double t : {0.0, 0.1, 0.25, 0.5, 0.9, 1.3, 2.0}) EXPECT_NEAR(sample_channel(ch, t)[0], p(t), 1e-6) << t;
}

TEST(SampleChannel, CubicSplineRotationIsNormalised) {
  const std::vector<float> values = {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0,  //
                                     0, 0, 1, 0, 0, 0, 0.7071068f, 0.7071068f, 0, 0, 0, 0};
  const Channel ch = channel(TargetPath::kRotation, Interpolation::kCubicSpline, {0, 1}, values);
  const std::vector<double> q = sample_channel(ch, 0.3);
  EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0, 1e-12);
}

TEST(SamplePose, WorldMatricesComposeParentBeforeChild) {
  Asset asset;
  asset.nodes.resize(2);
  asset.nodes[0].children = {1};
  asset.nodes[0].local.translation = {1, 0, 0};
  asset.nodes[1].parent = 0;
  asset.nodes[1].local.rotation = glm::angleAxis(M_PI / 2, Vec3<double>(0, 0, 1));
  asset.nodes[1].local.translation = {0, 2, 0};
  Clip clip;
  clip.channels.push_back(channel(TargetPath::kTranslation, Interpolation::kLinear, {0, 1}, {0, 0, 0, 0, 0, 4}));
  clip.channels.back().node = 0;
  const Pose pose = sample_pose(asset, &clip, 0.5);
  const glm::dvec4 p = pose.world[1] * glm::dvec4(1, 0, 0, 1);  // rotate to (0,1,0), + (0,2,0), + (0,0,2)
  EXPECT_NEAR(glm::distance(glm::dvec3(p), glm::dvec3(0, 3, 2)), 0, 1e-12);
  const Pose rest = sample_pose(asset, nullptr, 0.5);
  EXPECT_NEAR(glm::distance(glm::dvec3(rest.world[1] * glm::dvec4(1, 0, 0, 1)), glm::dvec3(1, 3, 0)), 0, 1e-12);
}

// InterpolationTest (Khronos): one node per clip; values computed by hand from the keys in the file and
// the formulas of glTF 2.0 Appendix C.
class InterpolationTestModel : public testing::Test {
protected:
  void SetUp() override {
    const std::filesystem::path path =
        std::filesystem::path(DQSKIN_SHARED_TESTDATA_DIR) / "InterpolationTest" / "InterpolationTest.glb";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared test data not found: " << path;
    asset_ = load_asset(path.string());
  }

  // Local value of `node` under clip `name` at time t: its world matrix, as none of these nodes has a parent.
  Mat4<double> world(const std::string& name, int node, double t) {
    for (const Clip& clip : asset_.clips)
      if (clip.name == name) return sample_pose(asset_, &clip, t).world[size_t(node)];
    ADD_FAILURE() << "no clip " << name;
    return Mat4<double>(1.0);
  }

  Asset asset_;
};

void expect_matrix_near(const Mat4<double>& a, const Mat4<double>& b, double tol) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], tol) << "(" << r << "," << c << ")";
}

Mat4<double> trs(Vec3<double> t, Quat<double> r, Vec3<double> s) {
  return glm::scale(glm::translate(Mat4<double>(1.0), t) * glm::mat4_cast(r), s);
}

TEST_F(InterpolationTestModel, StepScaleHoldsAndClampsBeforeTheFirstKey) {
  // keys 0.041667 → 1, 0.416667 → 0.5, 0.875 → 1; node 0 has no rest transform.
  expect_matrix_near(world("Step Scale", 0, 0.0), Mat4<double>(1.0), 1e-6);
  expect_matrix_near(world("Step Scale", 0, 0.5), trs({}, {1, 0, 0, 0}, Vec3<double>(0.5)), 1e-6);
  expect_matrix_near(world("Step Scale", 0, 0.87), trs({}, {1, 0, 0, 0}, Vec3<double>(0.5)), 1e-6);
}

TEST_F(InterpolationTestModel, LinearScaleIsLinearBetweenKeys) {
  // Halfway between 0.416667 (0.5) and 0.875 (1): 0.75; the rest translation stays.
  const double t = (0.416667 + 0.875) / 2;
  expect_matrix_near(world("Linear Scale", 3, t), trs({-3.2963297, 0, 6.4611435e-05}, {1, 0, 0, 0}, Vec3<double>(0.75)), 1e-5);
}

TEST_F(InterpolationTestModel, CubicSplineTranslationWithZeroTangentsEasesBetweenKeys) {
  // u = 0.5 between keys 0.416667 (y 10) and 0.833333 (y 6): h00 = h01 = 0.5, tangents 0 → y = 8.
  expect_matrix_near(world("CubicSpline Translation", 9, 0.625), trs({3.30518, 8, 0}, {1, 0, 0, 0}, Vec3<double>(1)), 1e-5);
  // u = 0.25: h00 = 2u³ − 3u² + 1 = 0.84375, h01 = 0.15625 → y = 0.84375·10 + 0.15625·6 = 9.375.
  expect_matrix_near(world("CubicSpline Translation", 9, 0.416667 + 0.25 * 0.416666),
                     trs({3.30518, 9.375, 0}, {1, 0, 0, 0}, Vec3<double>(1)), 1e-4);
}

TEST_F(InterpolationTestModel, CubicSplineRotationUsesScaledTangentsAndIsNormalised) {
  // Keys 0.416667 (z −0.382683, w 0.92388, out-tangent z −0.047891 w 0.998853) and 0.875 (z −0.707107,
  // w 0.707107, in-tangent z −0.035464 w 0.999371); u = 0.5: h00 = h01 = 0.5, h10 = 0.125, h11 = −0.125,
  // the tangents scaled by Δ = 0.458333.
  const double d = 0.875 - 0.416667;
  const double z = 0.5 * -0.382683 + d * 0.125 * -0.047891 + 0.5 * -0.707107 + d * -0.125 * -0.035464;
  const double w = 0.5 * 0.92388 + d * 0.125 * 0.998853 + 0.5 * 0.707107 + d * -0.125 * 0.999371;
  const double n = std::sqrt(z * z + w * w);
  expect_matrix_near(world("CubicSpline Rotation", 6, (0.416667 + 0.875) / 2),
                     trs({3.3350618, 3.3564124, 0}, Quat<double>(w / n, 0, 0, z / n), Vec3<double>(1)), 1e-5);
}

TEST_F(InterpolationTestModel, LinearRotationSlerpsTheShortWay) {
  // 135° and 180° about −z: halfway is 157.5°.
  const double half = 157.5 / 2 * M_PI / 180;
  expect_matrix_near(world("Linear Rotation", 7, (1.25 + 1.708333) / 2),
                     trs({-3.3113992, 3.3564124, 0}, Quat<double>(std::cos(half), 0, 0, -std::sin(half)),
                         Vec3<double>(0.99999994, 0.99999994, 1)),
                     1e-5);
}

TEST_F(InterpolationTestModel, StepTranslationClampsAfterTheLastKey) {
  expect_matrix_near(world("Step Translation", 8, 0.6), trs({0, 10, 0}, {1, 0, 0, 0}, Vec3<double>(1)), 1e-5);
  expect_matrix_near(world("Step Translation", 8, 5.0), trs({0, 6, 0}, {1, 0, 0, 0}, Vec3<double>(1)), 1e-5);
}

TEST_F(InterpolationTestModel, LinearTranslationIsLinearBetweenKeys) {
  expect_matrix_near(world("Linear Translation", 10, 0.625), trs({-3.297581, 8, 0}, {1, 0, 0, 0}, Vec3<double>(1)), 1e-5);
}

}  // namespace
}  // namespace dqskin
