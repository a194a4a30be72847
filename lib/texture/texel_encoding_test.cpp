#include "texel_encoding.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace dqskin::texture {
namespace {

TEST(TexelEncoding, NamesRoundTrip) {
  for (TexelType t : {TexelType::kFloat32, TexelType::kHalf, TexelType::kUnorm16, TexelType::kUnorm8}) {
    TexelType back{};
    ASSERT_TRUE(parse_texel_type(to_string(t), back));
    EXPECT_EQ(back, t);
  }
  TexelType t{};
  EXPECT_FALSE(parse_texel_type("float16", t));
}

TEST(TexelEncoding, UnormRoundTripIsWithinHalfAStep) {
  // Half a step of the range: (hi − lo) / (2 max), plus the float decode's rounding.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3.0, 5.0);
  for (uint32_t max : {255u, 65535u}) {
    const double lo = -3, hi = 5;
    double worst = 0;
    for (int i = 0; i < 100000; ++i) {
      const double x = u(rng);
      const uint32_t q = encode_unorm(x, lo, hi, max);
      ASSERT_LE(q, max);
      worst = std::max(worst, std::abs(double(decode_unorm(q, float(lo), float(hi), max)) - x));
    }
    EXPECT_LE(worst, (hi - lo) / (2.0 * max) + 8 * std::ldexp(1.0, -24) * 5);
    EXPECT_GT(worst, (hi - lo) / (2.0 * max) * 0.9) << "the bound is reached: the test can fail";
  }
}

TEST(TexelEncoding, UnormEndsAreExact) {
  EXPECT_EQ(encode_unorm(-2.0, -2.0, 6.0, 255), 0u);
  EXPECT_EQ(encode_unorm(6.0, -2.0, 6.0, 255), 255u);
  EXPECT_EQ(decode_unorm(255, -2.0f, 6.0f, 255), 6.0f);
  EXPECT_EQ(encode_unorm(1.0, 1.0, 1.0, 65535), 0u) << "an empty range stores 0";
}

TEST(TexelEncoding, HalfRoundsToNearestAndRefusesOverflow) {
  float r = 0;
  ASSERT_TRUE(to_half(1.0f + 1.0f / 4096, r));
  EXPECT_EQ(r, 1.0f) << "ties to even at 1 + 2^-12";
  ASSERT_TRUE(to_half(65504.0f, r));
  EXPECT_EQ(r, 65504.0f);
  EXPECT_FALSE(to_half(65520.0f, r)) << "rounds to infinity";
  EXPECT_FALSE(to_half(std::numeric_limits<float>::quiet_NaN(), r));
  // The rounding error never exceeds half of half_ulp.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-3000.0f, 3000.0f);
  for (int i = 0; i < 100000; ++i) {
    const float x = u(rng);
    ASSERT_TRUE(to_half(x, r));
    ASSERT_LE(std::abs(double(r) - double(x)), half_ulp(double(x)) / 2) << x;
  }
  EXPECT_EQ(half_ulp(1.0), std::ldexp(1.0, -10));
  EXPECT_EQ(half_ulp(1000.0), 0.5);
}

TEST(TexelEncoding, OctahedralRoundTripsEveryDirection) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  for (int i = 0; i < 100000; ++i) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
    const glm::dvec2 uv = octahedral_encode(n);
    ASSERT_LE(std::abs(uv.x) + 0.0, 1.0);
    ASSERT_LE(std::abs(uv.y) + 0.0, 1.0);
    const glm::dvec3 back = octahedral_decode(uv);
    ASSERT_NEAR(glm::length(back - n), 0.0, 1e-12) << n.x << " " << n.y << " " << n.z;
  }
  // The poles and the folded seam.
  for (const glm::dvec3 n : {glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1), glm::dvec3(1, 0, 0), glm::dvec3(0, -1, 0)})
    EXPECT_NEAR(glm::length(octahedral_decode(octahedral_encode(n)) - n), 0.0, 1e-15);
}

TEST(TexelEncoding, OctahedralQuantizedErrorIsBounded) {
  // 2 × 8 and 2 × 16 bits: the worst angle over many directions stays under the bound that docs/formats.md
  // states.
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  for (const auto& [max, bound_degrees] : {std::pair{255u, 1.0}, std::pair{65535u, 0.005}}) {
    double worst = 0;
    for (int i = 0; i < 200000; ++i) {
      const glm::dvec3 n = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
      const glm::dvec2 e = octahedral_encode(n) * 0.5 + 0.5;
      const glm::dvec2 q(encode_unorm(e.x, 0, 1, max), encode_unorm(e.y, 0, 1, max));
      const glm::dvec3 back = octahedral_decode(q / double(max) * 2.0 - 1.0);
      worst = std::max(worst, std::acos(std::clamp(glm::dot(back, n), -1.0, 1.0)) * 180 / std::numbers::pi);
    }
    EXPECT_LT(worst, bound_degrees) << max;
    EXPECT_GT(worst, bound_degrees / 10) << "the bound is not loose beyond use";
  }
}

}  // namespace
}  // namespace dqskin::texture
