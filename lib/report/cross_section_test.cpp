// The cross-section measure on synthetic rings.
#include "cross_section.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace dqskin::report_detail {
namespace {

// `n` points on a circle of `radius` about the line through `center` along z, at height z.
std::vector<glm::dvec3> ring(double radius, size_t n, glm::dvec3 center = {0, 0, 0}) {
  std::vector<glm::dvec3> out;
  for (size_t k = 0; k < n; ++k) {
    const double a = 2 * std::numbers::pi * double(k) / double(n);
    out.push_back(center + glm::dvec3(radius * std::cos(a), radius * std::sin(a), 0));
  }
  return out;
}

TEST(CrossSection, RingAroundTheAxisSpreadsHalfItsRadiusSquared) {
  EXPECT_NEAR(section_spread(ring(2.0, 24), {0, 0, 0}, {0, 0, 1}), 2.0, 1e-12);
  EXPECT_NEAR(section_spread(ring(0.5, 24), {0, 0, 5}, {0, 0, 1}), 0.125, 1e-12);  // the point's height does not count
}

TEST(CrossSection, CollapsedRingHasNoSpread) {
  EXPECT_NEAR(section_spread(ring(0.0, 24), {0, 0, 0}, {0, 0, 1}), 0.0, 1e-15);
  // Flattened to a segment through the axis: no area either.
  std::vector<glm::dvec3> flat = ring(1.0, 24);
  for (glm::dvec3& p : flat) p.y = 0;
  EXPECT_NEAR(section_spread(flat, {0, 0, 0}, {0, 0, 1}), 0.0, 1e-12);
}

TEST(CrossSection, TiltedRingShrinksByTheCosine) {
  // Turning the ring 60° about x halves its extent along y as seen along z.
  std::vector<glm::dvec3> tilted = ring(1.0, 36);
  const Quat<double> turn = glm::angleAxis(glm::radians(60.0), glm::dvec3(1, 0, 0));
  for (glm::dvec3& p : tilted) p = turn * p;
  EXPECT_NEAR(section_spread(tilted, {0, 0, 0}, {0, 0, 1}), 0.5 * 0.5, 1e-12);
}

TEST(CrossSection, SlicesSplitTheZoneAlongTheAxis) {
  std::vector<ZoneVertex> zone;
  for (int s = 0; s <= 8; ++s)
    for (int k = 0; k < 4; ++k) zone.push_back({{}, {}, double(s)});
  const auto slices = slice_zone(zone);
  ASSERT_EQ(slices.size(), size_t(kSlices));  // nine stations in eight slices: the last holds two
  EXPECT_EQ(slices.back().size(), 8u);
  // Fewer than 3 vertices in a slice: dropped.
  EXPECT_TRUE(slice_zone({{{}, {}, 0.0}, {{}, {}, 1.0}}).empty());
}

}  // namespace
}  // namespace dqskin::report_detail
