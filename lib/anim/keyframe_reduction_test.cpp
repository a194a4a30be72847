// Keyframe reduction on curves with known answers: a straight motion needs its two ends, a curve keeps
// fewer frames as the budget grows and every frame stays within it, ties go to the earliest frame.
#include "keyframe_reduction.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace dqskin {
namespace {

// A one-dimensional motion x(i), interpolated linearly in the frame index between keys.
InterpolationError error_of(const std::vector<double>& x) {
  return [&x](size_t i, size_t a, size_t b) {
    const double s = double(i - a) / double(b - a);
    return std::abs((1 - s) * x[a] + s * x[b] - x[i]);
  };
}

// The largest error over every frame with `keys`.
double worst(const std::vector<double>& x, const std::vector<size_t>& keys) {
  double w = 0;
  for (size_t k = 0; k + 1 < keys.size(); ++k)
    for (size_t i = keys[k] + 1; i < keys[k + 1]; ++i) w = std::max(w, error_of(x)(i, keys[k], keys[k + 1]));
  return w;
}

std::vector<double> sine(size_t frames) {
  std::vector<double> x;
  for (size_t i = 0; i < frames; ++i) x.push_back(std::sin(double(i) * 0.1));
  return x;
}

TEST(KeyframeReduction, StraightMotionKeepsItsEnds) {
  std::vector<double> x;
  for (size_t i = 0; i < 50; ++i) x.push_back(0.25 * double(i));
  EXPECT_EQ(reduce_keyframes(x.size(), 1e-9, error_of(x), 2), (std::vector<size_t>{0, 49}));
}

TEST(KeyframeReduction, OneAndTwoFramesAreAllKeys) {
  const std::vector<double> x = {1.0, 3.0};
  EXPECT_EQ(reduce_keyframes(1, 0.5, error_of(x), 1), (std::vector<size_t>{0}));
  EXPECT_EQ(reduce_keyframes(2, 0.5, error_of(x), 1), (std::vector<size_t>{0, 1}));
}

TEST(KeyframeReduction, ZeroBudgetKeepsEveryFrameOfACurve) {
  const std::vector<double> x = sine(40);
  EXPECT_EQ(reduce_keyframes(x.size(), 0.0, error_of(x), 2).size(), x.size());
}

TEST(KeyframeReduction, EveryFrameIsWithinTheBudgetAndALargerBudgetKeepsFewer) {
  const std::vector<double> x = sine(100);
  size_t previous = x.size() + 1;
  for (double budget : {1e-4, 1e-3, 1e-2, 1e-1}) {
    SCOPED_TRACE(budget);
    const std::vector<size_t> keys = reduce_keyframes(x.size(), budget, error_of(x), 3);
    EXPECT_LE(worst(x, keys), budget);
    EXPECT_EQ(keys.front(), 0u);
    EXPECT_EQ(keys.back(), x.size() - 1);
    EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()));
    EXPECT_LT(keys.size(), previous);
    previous = keys.size();
  }
}

TEST(KeyframeReduction, TheTurningPointBecomesAKeyAndTiesGoToTheEarliest) {
  // A tent: up to frame 6, down after it. The only key needed besides the ends is the peak.
  std::vector<double> tent;
  for (size_t i = 0; i < 13; ++i) tent.push_back(i <= 6 ? double(i) : double(12 - i));
  EXPECT_EQ(reduce_keyframes(tent.size(), 1e-9, error_of(tent), 2), (std::vector<size_t>{0, 6, 12}));
  // A plateau from frame 3 to 9: frames 3 … 9 err alike; the first of them is the key, then frame 9.
  std::vector<double> plateau = {0, 1, 2, 3, 3, 3, 3, 3, 3, 3, 2, 1, 0};
  EXPECT_EQ(reduce_keyframes(plateau.size(), 1e-9, error_of(plateau), 2), (std::vector<size_t>{0, 3, 9, 12}));
}

TEST(KeyframeReduction, ThreadsDoNotChangeTheKeys) {
  const std::vector<double> x = sine(200);
  EXPECT_EQ(reduce_keyframes(x.size(), 1e-3, error_of(x), 1), reduce_keyframes(x.size(), 1e-3, error_of(x), 4));
}

}  // namespace
}  // namespace dqskin
