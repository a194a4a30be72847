// Helpers shared by the math tests: seeded random poses and comparisons that print both operands.
#pragma once

#include "dqskin/dual_quat.hpp"

#include <glm/gtx/string_cast.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace dqskin::test {

// A seeded generator, so every run of a property test sees the same inputs.
class Random {
public:
  explicit Random(unsigned seed) : engine_(seed) {}

  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(engine_); }

  Vec3<double> vec3(double extent) {
    return {uniform(-extent, extent), uniform(-extent, extent), uniform(-extent, extent)};
  }

  // Uniformly distributed unit quaternion (Shoemake's subgroup algorithm).
  Quat<double> rotation() {
    const double u1 = uniform(0, 1), u2 = uniform(0, 2 * M_PI), u3 = uniform(0, 2 * M_PI);
    const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    return Quat<double>(  // GLM 0.9.9 constructor order: w, x, y, z
        b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3));
  }

  // Random rigid pose: any rotation, translation within ±extent on each axis.
  DualQuat<double> pose(double extent = 10) { return from_rotation_translation(rotation(), vec3(extent)); }

  // n convex weights (non-negative, summing to 1).
  std::vector<double> convex_weights(size_t n) {
    std::vector<double> w(n);
    double sum = 0;
    for (double& x : w) sum += (x = uniform(0, 1));
    for (double& x : w) x /= sum;
    return w;
  }

private:
  std::mt19937_64 engine_;
};

// Largest absolute difference over all eight components; infinity when any is NaN, so that a NaN
// result can never pass a tolerance (std::max would drop it).
template <typename T>
T max_abs_diff(const DualQuat<T>& a, const DualQuat<T>& b) {
  T m = 0;
  for (int i = 0; i < 4; ++i) {
    for (const T d : {std::abs(a.real[i] - b.real[i]), std::abs(a.dual[i] - b.dual[i])}) {
      if (!(d <= m)) m = std::isnan(d) ? std::numeric_limits<T>::infinity() : d;
    }
  }
  return m;
}

// Same pose: equal up to the sign (q and −q are one rigid transformation).
template <typename T>
T pose_diff(const DualQuat<T>& a, const DualQuat<T>& b) {
  return std::min(max_abs_diff(a, b), max_abs_diff(a, -b));
}

}  // namespace dqskin::test

#define EXPECT_DUALQUAT_NEAR(a, b, tol) \
  EXPECT_LE(::dqskin::test::max_abs_diff((a), (b)), (tol)) << "  a = " << glm::to_string((a).real) << " + ε" \
      << glm::to_string((a).dual) << "\n  b = " << glm::to_string((b).real) << " + ε" << glm::to_string((b).dual)

#define EXPECT_SAME_POSE(a, b, tol) \
  EXPECT_LE(::dqskin::test::pose_diff((a), (b)), (tol)) << "  a = " << glm::to_string((a).real) << " + ε" \
      << glm::to_string((a).dual) << "\n  b = " << glm::to_string((b).real) << " + ε" << glm::to_string((b).dual)
