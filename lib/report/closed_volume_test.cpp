// Closedness and the divergence-theorem volume on a cube and a sphere.
#include "closed_volume.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace dqskin::report_detail {
namespace {

// A FrameView over one primitive's positions, and its triangles as BatchTriangles.
struct Soup {
  std::vector<float> positions;
  std::vector<std::array<uint32_t, 3>> triangles;
  FrameView view() const {
    FrameView f;
    f.primitives.push_back({positions.size() / 3, positions, {}, {}});
    return f;
  }
  std::vector<BatchTriangle> batch() const {
    std::vector<BatchTriangle> out;
    for (const auto& t : triangles) out.push_back({0, t});
    return out;
  }
};

Soup cube(float side) {
  Soup s;
  for (int v = 0; v < 8; ++v)
    for (int c = 0; c < 3; ++c) s.positions.push_back(((v >> c) & 1) ? side : 0.0f);
  // Two counter-clockwise (seen from outside) triangles per face.
  s.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return s;
}

// A UV sphere of `radius` with poles: closed, its volume tends to 4/3 π r³.
Soup sphere(double radius, int rings, int segments) {
  Soup s;
  auto add = [&](double theta, double phi) {
    s.positions.push_back(float(radius * std::sin(theta) * std::cos(phi)));
    s.positions.push_back(float(radius * std::sin(theta) * std::sin(phi)));
    s.positions.push_back(float(radius * std::cos(theta)));
  };
  add(0, 0);  // north pole 0
  for (int r = 1; r < rings; ++r)
    for (int k = 0; k < segments; ++k) add(std::numbers::pi * r / rings, 2 * std::numbers::pi * k / segments);
  add(std::numbers::pi, 0);  // south pole
  const uint32_t south = uint32_t(s.positions.size() / 3 - 1);
  auto at = [&](int r, int k) { return uint32_t(1 + (r - 1) * segments + (k % segments)); };
  for (int k = 0; k < segments; ++k) {
    s.triangles.push_back({0, at(1, k), at(1, k + 1)});
    s.triangles.push_back({south, at(rings - 1, k + 1), at(rings - 1, k)});
    for (int r = 1; r + 1 < rings; ++r) {
      s.triangles.push_back({at(r, k), at(r + 1, k), at(r + 1, k + 1)});
      s.triangles.push_back({at(r, k), at(r + 1, k + 1), at(r, k + 1)});
    }
  }
  return s;
}

TEST(ClosedVolume, CubeIsClosedAndHoldsItsVolume) {
  const Soup s = cube(2.0f);
  EXPECT_TRUE(is_closed(s.triangles));
  const std::vector<BatchTriangle> t = s.batch();
  EXPECT_NEAR(signed_volume(t, s.view()), 8.0, 1e-12);
}

TEST(ClosedVolume, SphereApproachesFourThirdsPiRCubed) {
  const Soup s = sphere(1.5, 64, 128);
  EXPECT_TRUE(is_closed(s.triangles));
  const std::vector<BatchTriangle> t = s.batch();
  const double exact = 4.0 / 3.0 * std::numbers::pi * 1.5 * 1.5 * 1.5;
  EXPECT_NEAR(signed_volume(t, s.view()) / exact, 1.0, 2e-3);
}

TEST(ClosedVolume, MissingOrDoubledTriangleIsOpen) {
  Soup s = cube(1.0f);
  s.triangles.pop_back();
  EXPECT_FALSE(is_closed(s.triangles));
  Soup d = cube(1.0f);
  d.triangles.push_back(d.triangles.front());  // an edge shared by three triangles
  EXPECT_FALSE(is_closed(d.triangles));
  EXPECT_FALSE(is_closed({}));
}

TEST(ClosedVolume, InconsistentWindingIsNotClosed) {
  Soup s = cube(1.0f);
  std::swap(s.triangles.front()[1], s.triangles.front()[2]);  // one face turned inside out
  EXPECT_FALSE(is_closed(s.triangles));
}

}  // namespace
}  // namespace dqskin::report_detail
