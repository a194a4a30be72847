// One channel reduced under a budget: what the viewer interpolates between the kept keys stays within it
// at every time, not only at the input's keys (a dense grid of times measures it here, through
// sample_channel, the sampler every command uses).
#include "channel_reduction.hpp"

#include "dqskin/animation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace dqskin::optimize_detail {
namespace {

NodeLevers unit_levers() {
  NodeLevers l;
  l.moves_vertices = true;
  l.rotation = l.translation = l.scale = 1;
  return l;
}

// A translation channel along x with these values, one key a tenth of a second.
Channel along_x(const std::vector<float>& xs, Interpolation interpolation = Interpolation::kLinear) {
  Channel ch;
  ch.node = 0;
  ch.path = TargetPath::kTranslation;
  ch.interpolation = interpolation;
  ch.components = 3;
  for (size_t k = 0; k < xs.size(); ++k) {
    ch.times.push_back(float(k) * 0.1f);
    ch.values.insert(ch.values.end(), {xs[k], 0.0f, 0.0f});
  }
  return ch;
}

// The largest distance between the two channels' values at 64 times of every input segment.
double worst_gap(const Channel& input, const Channel& reduced) {
  double worst = 0;
  for (size_t k = 0; k + 1 < input.times.size(); ++k)
    for (int j = 0; j <= 64; ++j) {
      const double t = double(input.times[k]) + (double(input.times[k + 1]) - double(input.times[k])) * j / 64.0;
      const std::vector<double> a = sample_channel(input, t), b = sample_channel(reduced, t);
      double d = 0;
      for (size_t c = 0; c < a.size(); ++c) d += (a[c] - b[c]) * (a[c] - b[c]);
      worst = std::max(worst, std::sqrt(d));
    }
  return worst;
}

// Plateaus a step of 0.9 apart (0, 0.9, 1.8, 0.9, 0), ten keys each: with a budget of 1 the line through
// them needs three keys, STEP two (0 held until the last 0.9 key, then 0.9 to the end).
TEST(ChannelReduction, PlateausBecomeStepWhereThatHoldsAtEveryTime) {
  std::vector<float> xs;
  for (float level : {0.0f, 0.9f, 1.8f, 0.9f, 0.0f}) xs.insert(xs.end(), 10, level);
  const Channel input = along_x(xs);
  const ReducedChannel r = reduce_channel(input, unit_levers(), 1.0, nullptr, {}, 1);
  ASSERT_FALSE(r.dropped);
  EXPECT_EQ(r.channel.interpolation, Interpolation::kStep);
  EXPECT_EQ(r.channel.times.size(), 2u);
  EXPECT_LE(worst_gap(input, r.channel), 1.0);

  const ReducedChannel linear = reduce_channel(input, unit_levers(), 1.0, nullptr, {true, false}, 1);
  EXPECT_EQ(linear.channel.interpolation, Interpolation::kLinear) << "the lever switched off";
  EXPECT_EQ(linear.channel.times.size(), 3u);
  EXPECT_LE(worst_gap(input, linear.channel), 1.0);
}

// A jump of 5 in one segment: as STEP the value would sit 5 away just before the jump's end, however few keys
// it takes; one segment changing by more than the budget keeps a channel LINEAR.
TEST(ChannelReduction, AJumpOverTheBudgetStaysLinear) {
  std::vector<float> xs;
  for (int k = 0; k < 20; ++k) xs.push_back(k < 10 ? 0.0f : 5.0f);
  const Channel input = along_x(xs);
  const ReducedChannel r = reduce_channel(input, unit_levers(), 1.0, nullptr, {}, 1);
  EXPECT_EQ(r.channel.interpolation, Interpolation::kLinear);
  EXPECT_EQ(r.channel.times.size(), 4u) << "both ends of each plateau";
  EXPECT_LT(worst_gap(input, r.channel), 1e-12);
}

// A CUBICSPLINE channel (in-tangent, value, out-tangent a key) of a slow ease: three floats a key more than
// LINEAR, so its linear equivalent is smaller and replaces it, within the budget along the whole curve.
TEST(ChannelReduction, ASmoothCubicBecomesLinearWithinTheBudget) {
  Channel cubic;
  cubic.node = 0;
  cubic.path = TargetPath::kTranslation;
  cubic.interpolation = Interpolation::kCubicSpline;
  cubic.components = 3;
  for (int k = 0; k < 12; ++k) {
    const float x = std::sin(float(k) * 0.5f), slope = 5.0f * std::cos(float(k) * 0.5f);  // d/dt of sin(5t)
    cubic.times.push_back(float(k) * 0.1f);
    cubic.values.insert(cubic.values.end(), {slope, 0, 0, x, 0, 0, slope, 0, 0});
  }
  const ReducedChannel r = reduce_channel(cubic, unit_levers(), 0.01, nullptr, {}, 1);
  ASSERT_FALSE(r.dropped);
  EXPECT_EQ(r.channel.interpolation, Interpolation::kLinear);
  EXPECT_LT(r.channel.times.size() * 4, cubic.times.size() * 10) << "fewer bytes than the cubic keys";
  EXPECT_LE(worst_gap(cubic, r.channel), 0.01);
  EXPECT_EQ(r.channel.times.front(), cubic.times.front());
  EXPECT_EQ(r.channel.times.back(), cubic.times.back());

  const ReducedChannel kept = reduce_channel(cubic, unit_levers(), 0.01, nullptr, {true, false}, 1);
  EXPECT_EQ(kept.channel.interpolation, Interpolation::kCubicSpline) << "the lever switched off";
  EXPECT_EQ(kept.channel.values, cubic.values);
}

// A budget too small for a linear equivalent of fewer bytes keeps the cubic keys as they are.
TEST(ChannelReduction, ACubicWhoseLinearEquivalentIsLargerStays) {
  Channel cubic;
  cubic.node = 0;
  cubic.path = TargetPath::kTranslation;
  cubic.interpolation = Interpolation::kCubicSpline;
  cubic.components = 3;
  for (int k = 0; k < 4; ++k) {
    cubic.times.push_back(float(k));
    const float x = float(k % 2), slope = k % 2 ? -4.0f : 4.0f;  // a wiggle between every two keys
    cubic.values.insert(cubic.values.end(), {slope, 0, 0, x, 0, 0, slope, 0, 0});
  }
  const ReducedChannel r = reduce_channel(cubic, unit_levers(), 1e-6, nullptr, {}, 1);
  EXPECT_EQ(r.channel.interpolation, Interpolation::kCubicSpline);
  EXPECT_EQ(r.channel.values, cubic.values);
}

}  // namespace
}  // namespace dqskin::optimize_detail
