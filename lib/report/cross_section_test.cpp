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

TEST(CrossSection, RingSpreadsHalfItsRadiusSquaredWhereverItIs) {
  const Spread s = section_spread(ring(2.0, 24), {0, 0, 1});
  EXPECT_NEAR(s.area, 2.0, 1e-12);
  EXPECT_NEAR(s.major, 2.0, 1e-6);  // a double eigenvalue: its square root of rounding shows
  EXPECT_NEAR(s.minor, 2.0, 1e-6);
  EXPECT_NEAR(section_spread(ring(0.5, 24, {3, -1, 5}), {0, 0, 1}).area, 0.125, 1e-12);
}

TEST(CrossSection, CollapsedRingHasNoSpread) {
  EXPECT_NEAR(section_spread(ring(0.0, 24, {1, 2, 3}), {0, 0, 1}).area, 0.0, 1e-15);
  // Flattened to a segment through the axis: no area either.
  std::vector<glm::dvec3> flat = ring(1.0, 24);
  for (glm::dvec3& p : flat) p.y = 0;
  const Spread s = section_spread(flat, {0, 0, 1});
  EXPECT_NEAR(s.area, 0.0, 1e-12);
  EXPECT_NEAR(s.minor, 0.0, 1e-12);
  EXPECT_NEAR(s.major, 0.5, 1e-12);
}

TEST(CrossSection, TiltedRingShrinksByTheCosine) {
  // Turning the ring 60° about x halves its extent along y as seen along z.
  std::vector<glm::dvec3> tilted = ring(1.0, 36);
  const Quat<double> turn = glm::angleAxis(glm::radians(60.0), glm::dvec3(1, 0, 0));
  for (glm::dvec3& p : tilted) p = turn * p;
  EXPECT_NEAR(section_spread(tilted, {0, 0, 1}).area, 0.5 * 0.5, 1e-12);
}

TEST(CrossSection, SlicesSplitTheZoneAlongTheAxis) {
  std::vector<ZoneVertex> zone;
  for (int s = 0; s <= 8; ++s)
    for (size_t k = 0; k < 2 * kSliceVertices; ++k) zone.push_back({{}, {}, double(s)});
  const auto slices = slice_zone(zone);
  ASSERT_EQ(slices.size(), size_t(kSlices));  // nine stations in eight slices: the last holds two
  EXPECT_EQ(slices.back().size(), 4 * kSliceVertices);
  // A small zone gets fewer slices: here two stations of 2·kSliceVertices, one slice each.
  zone.resize(4 * kSliceVertices);
  EXPECT_EQ(slice_zone(zone).size(), 2u);
  // Too few vertices in a slice: dropped.
  zone.resize(kSliceVertices - 1);
  EXPECT_TRUE(slice_zone(zone).empty());
}

}  // namespace
}  // namespace dqskin::report_detail
