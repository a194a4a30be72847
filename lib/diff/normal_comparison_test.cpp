// How the geometric diff compares normals (normal_comparison.hpp, frame_measure.hpp): smooth vertex normals
// where both files have one at a point, face normals elsewhere.
#include "normal_comparison.hpp"
#include "frame_measure.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace dqskin::diff_detail {
namespace {

// Two triangles of a square folded 90° along its diagonal, as a flat-shaded file stores them: six vertices,
// each with its face's normal. `split` false: the two vertices at each shared position get one (averaged)
// normal, as a smooth file stores them.
struct Folded {
  DiffSide side;
  PosedSurface surface;
};

Folded folded(bool split, bool normals = true) {
  Folded f;
  const glm::dvec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
  f.surface.positions = {a, b, c, b, c, d};
  const glm::dvec3 n1(0, 0, 1), n2 = glm::normalize(glm::dvec3(1, 1, 1));
  if (!normals) f.surface.normals.assign(6, glm::dvec3(0));
  else if (split) f.surface.normals = {n1, n1, n1, n2, n2, n2};
  else f.surface.normals = {n1, glm::normalize(n1 + n2), glm::normalize(n1 + n2), glm::normalize(n1 + n2), glm::normalize(n1 + n2), n2};
  f.side.vertices = 6;
  f.side.first_vertex = {0};
  f.side.primitive_size = {6};
  f.side.file_normals = {uint8_t(normals)};
  f.side.triangles = {0, 1, 2, 3, 4, 5};
  f.side.on_surface.assign(6, 1);
  return f;
}

Correspondence identity_of(const DiffSide& side) {
  Correspondence c;
  for (uint32_t v = 0; v < side.vertices; ++v) {
    c.vertices.push_back(v);
    SurfacePoint p;
    p.vertex[0] = p.vertex[1] = p.vertex[2] = v;
    c.points.push_back(p);
  }
  c.joint.assign(side.vertices, 0);
  return c;
}

TEST(SmoothVertices, SplitNormalsAtOnePositionAreNotSmooth) {
  const Folded split = folded(true);
  EXPECT_EQ(smooth_vertices(split.side, split.surface), (std::vector<uint8_t>{1, 0, 0, 0, 0, 1}));
  const Folded smooth = folded(false);
  EXPECT_EQ(smooth_vertices(smooth.side, smooth.surface), (std::vector<uint8_t>(6, 1)));
  const Folded none = folded(true, false);  // no NORMAL: drawn flat, never smooth
  EXPECT_EQ(smooth_vertices(none.side, none.surface), (std::vector<uint8_t>(6, 0)));
}

TEST(SmoothVertices, NormalsWithinADegreeAreOne) {
  Folded f = folded(false);
  f.surface.normals[3] = glm::normalize(f.surface.normals[3] + glm::dvec3(0.01, 0, 0));  // about 0.4°
  EXPECT_EQ(smooth_vertices(f.side, f.surface)[1], 1);
  f.surface.normals[3] = glm::normalize(f.surface.normals[3] + glm::dvec3(0.05, 0, 0));  // over 2°
  EXPECT_EQ(smooth_vertices(f.side, f.surface)[1], 0);
}

TEST(PlanNormalComparison, FacesWhereACornerIsNotSmoothOnEitherSide) {
  const Folded split = folded(true), smooth = folded(false);
  Correspondence c = identity_of(split.side);
  const std::vector<uint8_t> s_split = smooth_vertices(split.side, split.surface);
  const std::vector<uint8_t> s_smooth = smooth_vertices(smooth.side, smooth.surface);
  plan_normal_comparison(split.side, s_split, s_smooth, c);
  EXPECT_EQ(c.smooth, s_split);
  EXPECT_EQ(c.faces, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
  // Smooth from, split onto: the same, because the surface point's vertices are not smooth.
  plan_normal_comparison(smooth.side, s_smooth, s_split, c);
  EXPECT_EQ(c.smooth, s_split);
  EXPECT_EQ(c.faces.size(), 6u);
  // Smooth on both sides: vertex normals only.
  plan_normal_comparison(smooth.side, s_smooth, s_smooth, c);
  EXPECT_EQ(c.smooth, s_smooth);
  EXPECT_TRUE(c.faces.empty());
}

SideFrame frame_of(const PosedSurface& s) {
  SideFrame f;
  for (size_t v = 0; v < s.positions.size(); ++v)
    for (int k = 0; k < 3; ++k) f.positions.push_back(float(s.positions[v][k])), f.normals.push_back(float(s.normals[v][k]));
  return f;
}

double normal_figure(const Folded& a, const Folded& b) {
  Correspondence c = identity_of(a.side);
  plan_normal_comparison(a.side, smooth_vertices(a.side, a.surface), smooth_vertices(b.side, b.surface), c);
  FrameResult r;
  r.joint_max.assign(1, -1.0f);
  LargestErrors largest;
  largest.reset(1);
  double direction = 0;
  measure(frame_of(a.surface), frame_of(b.surface), c, 1, 1, 'A', r, largest, direction);
  return r.figures.max_normal_degrees;
}

TEST(MeasureNormals, FlatShadedFacesAgreeWithThemselvesAndShowATurnedFace) {
  const Folded split = folded(true);
  // The vertex normals of the folded square differ by 54.7° at a shared position; compared as faces the
  // same geometry reads 0.
  EXPECT_EQ(normal_figure(split, split), 0.0);
  EXPECT_EQ(normal_figure(folded(true, false), folded(true, false)), 0.0);
  Folded turned = split;
  turned.surface.positions[5] = glm::dvec3(0, 0, 2);  // the second face tilts by 15.8°: (1, 1, 1) to (2, 2, 1)
  EXPECT_NEAR(normal_figure(split, turned), 15.79, 0.01);
}

}  // namespace
}  // namespace dqskin::diff_detail
