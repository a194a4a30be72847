// The closest-point index of the geometric diff against brute force: every triangle's exact closest point,
// found by the same region test and by dense sampling.
#include "surface_correspondence.hpp"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <limits>
#include <random>

namespace dqskin::diff_detail {
namespace {

glm::dvec3 point_of(const glm::dvec3& w, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return w.x * a + w.y * b + w.z * c;
}

TEST(ClosestPointWeights, MatchesDenseSamplingInEveryRegion) {
  const glm::dvec3 a(0, 0, 0), b(2, 0, 0), c(0.5, 1.5, 0);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1.5, 3.0);
  for (int trial = 0; trial < 200; ++trial) {
    const glm::dvec3 p(coordinate(random), coordinate(random), coordinate(random) * 0.5);
    const glm::dvec3 w = closest_point_weights(p, a, b, c);
    EXPECT_NEAR(w.x + w.y + w.z, 1.0, 1e-12);
    EXPECT_GE(std::min({w.x, w.y, w.z}), -1e-12);
    const double found = glm::length(point_of(w, a, b, c) - p);
    // No point of a 400 x 400 barycentric grid is closer (the grid's spacing bounds what it can miss).
    double sampled = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= 400; ++i)
      for (int j = 0; i + j <= 400; ++j)
        sampled = std::min(sampled, glm::length(point_of({1 - (i + j) / 400.0, i / 400.0, j / 400.0}, a, b, c) - p));
    EXPECT_LE(found, sampled + 1e-12) << "trial " << trial;
    EXPECT_GE(found, sampled - 0.01) << "trial " << trial;
  }
}

// A bumpy grid of triangles with a few long, thin ones across it: the index must find what trying every
// triangle finds.
TEST(SurfaceIndex, FindsTheSameDistanceAsEveryTriangle) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<glm::dvec3> positions;
  std::vector<uint32_t> triangles;
  const int n = 20;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) positions.emplace_back(x * 0.1, y * 0.1, 0.05 * unit(random));
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const uint32_t i = uint32_t(y * (n + 1) + x);
      triangles.insert(triangles.end(), {i, i + 1, i + uint32_t(n) + 1, i + 1, i + uint32_t(n) + 2, i + uint32_t(n) + 1});
    }
  for (int k = 0; k < 3; ++k) {  // long triangles above the grid
    const uint32_t first = uint32_t(positions.size());
    positions.emplace_back(-0.5, unit(random) * 2, 0.3 + k * 0.1);
    positions.emplace_back(2.5, unit(random) * 2, 0.3 + k * 0.1);
    positions.emplace_back(1.0, unit(random) * 2, 0.35 + k * 0.1);
    triangles.insert(triangles.end(), {first, first + 1, first + 2});
  }
  const SurfaceIndex index(positions, triangles);
  std::uniform_real_distribution<double> coordinate(-0.5, 2.5);
  for (int q = 0; q < 500; ++q) {
    const glm::dvec3 p(coordinate(random), coordinate(random), coordinate(random) - 1.0);
    double brute = std::numeric_limits<double>::infinity();
    for (size_t t = 0; t < triangles.size(); t += 3) {
      const glm::dvec3 a = positions[triangles[t]], b = positions[triangles[t + 1]], c = positions[triangles[t + 2]];
      brute = std::min(brute, glm::length(point_of(closest_point_weights(p, a, b, c), a, b, c) - p));
    }
    const SurfacePoint s = index.closest(p);
    glm::dvec3 found(0);
    for (int k = 0; k < 3; ++k) found += double(s.weight[k]) * positions[s.vertex[k]];
    // Within the tie window (1e-4 of the diagonal, about 3.3e-4 here) of the true distance.
    EXPECT_LE(double(s.distance), brute + 3.5e-4) << "query " << q;
    EXPECT_NEAR(glm::length(found - p), double(s.distance), 1e-6) << "query " << q;
  }
}

// At a crease, split vertices share positions: the face whose normals match the query's wins.
TEST(SurfaceIndex, BreaksTiesAtACreaseByNormal) {
  // Two faces of a box edge along x: the top (normal +y) and the front (normal +z), with their own vertices.
  const std::vector<glm::dvec3> positions = {{0, 1, 1}, {1, 1, 1}, {0, 1, 0},   // top
                                             {0, 1, 1}, {1, 1, 1}, {0, 0, 1}};  // front
  const std::vector<glm::dvec3> normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  const std::vector<uint32_t> triangles = {0, 2, 1, 3, 4, 5};
  const SurfaceIndex index(positions, triangles, normals);
  const glm::dvec3 on_edge(0.5, 1, 1);
  EXPECT_EQ(index.closest(on_edge, {0, 0, 1}).vertex[2], 5u);  // the front's third vertex
  const SurfacePoint top = index.closest(on_edge, {0, 1, 0});
  EXPECT_LT(top.vertex[0], 3u);
  EXPECT_EQ(top.distance, 0.0f);
}

TEST(SurfaceIndex, IgnoresTrianglesWithoutArea) {
  const std::vector<glm::dvec3> positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const std::vector<uint32_t> triangles = {0, 1, 2};
  EXPECT_TRUE(SurfaceIndex(positions, triangles).empty());
}

}  // namespace
}  // namespace dqskin::diff_detail
