#include "frame_measure.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dqskin::diff_detail {
namespace {

// The face normal of the triangle a, b, c (not unit), and whether it has one: a sliver whose sides are
// within 1e-6 rad of parallel has a normal that rounding turns anywhere.
bool face_normal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, glm::vec3& n) {
  const glm::vec3 e1 = b - a, e2 = c - a;
  n = glm::cross(e1, e2);
  return glm::dot(n, n) > 1e-12f * glm::dot(e1, e1) * glm::dot(e2, e2);
}

// The faces of one direction: each listed triangle of `from` against the triangle its corners' surface
// points (`point`, this frame) make; the largest angle goes into r's normal figure, measured exactly once
// as measure's is.
void measure_faces(const SideFrame& from_frame, const Correspondence& c, const std::vector<float>& point,
                   FrameResult& r) {
  auto from = [&](uint32_t i) { return at(from_frame.positions, c.vertices[i]); };
  auto onto = [&](uint32_t i) { return glm::vec3(point[3 * size_t(i)], point[3 * size_t(i) + 1], point[3 * size_t(i) + 2]); };
  float min_cosine = 2;
  size_t worst = SIZE_MAX;
  for (size_t f = 0; f + 2 < c.faces.size(); f += 3) {
    glm::vec3 m, n;
    if (!face_normal(from(c.faces[f]), from(c.faces[f + 1]), from(c.faces[f + 2]), m) ||
        !face_normal(onto(c.faces[f]), onto(c.faces[f + 1]), onto(c.faces[f + 2]), n))
      continue;
    const float cosine = glm::dot(m, n) / std::sqrt(glm::dot(m, m) * glm::dot(n, n));
    if (cosine < min_cosine) min_cosine = cosine, worst = f;
  }
  if (worst == SIZE_MAX) return;
  auto exact = [](const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
    return glm::cross(glm::dvec3(p1) - glm::dvec3(p0), glm::dvec3(p2) - glm::dvec3(p0));
  };
  const glm::dvec3 m = exact(from(c.faces[worst]), from(c.faces[worst + 1]), from(c.faces[worst + 2]));
  const glm::dvec3 n = exact(onto(c.faces[worst]), onto(c.faces[worst + 1]), onto(c.faces[worst + 2]));
  const double angle = std::atan2(glm::length(glm::cross(m, n)), glm::dot(m, n));
  r.figures.max_normal_degrees = std::max(r.figures.max_normal_degrees, angle * 180.0 / M_PI);
}

}  // namespace

void measure(const SideFrame& from_frame, const SideFrame& onto_frame, const Correspondence& c, double warn, double fail,
             char side, FrameResult& r, LargestErrors& largest, double& direction_max) {
  const float* P = onto_frame.positions.data();
  const float* N = onto_frame.normals.data();
  const float* A = from_frame.positions.data();
  const float* M = from_frame.normals.data();
  // Two passes: the distances and normal cosines without a branch, so that the fetches of many samples
  // are in flight at once; then the reductions over them.
  const size_t count = c.vertices.size();
  thread_local std::vector<float> distance, cosine, point;
  distance.resize(count);
  cosine.resize(count);
  point.resize(3 * count);  // each surface point at this frame, for the faces
  for (size_t i = 0; i < count; ++i) {
    const size_t a = 3 * size_t(c.vertices[i]);
    const SurfacePoint& s = c.points[i];
    float* p = &point[3 * i];
    float n[3] = {0, 0, 0};
    p[0] = p[1] = p[2] = 0;
    for (int k = 0; k < 3; ++k) {
      const size_t o = 3 * size_t(s.vertex[k]);
      for (int j = 0; j < 3; ++j) p[j] += s.weight[k] * P[o + size_t(j)], n[j] += s.weight[k] * N[o + size_t(j)];
    }
    const float dx = A[a] - p[0], dy = A[a + 1] - p[1], dz = A[a + 2] - p[2];
    distance[i] = std::sqrt(dx * dx + dy * dy + dz * dz);
    const float mm = M[a] * M[a] + M[a + 1] * M[a + 1] + M[a + 2] * M[a + 2];
    const float nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    const float dot = M[a] * n[0] + M[a + 1] * n[1] + M[a + 2] * n[2];
    // 2 (no angle) where the normals are not compared or either is missing: never the smallest cosine.
    cosine[i] = c.smooth[i] && mm > 0 && nn > 1e-12f ? dot / std::sqrt(mm * nn) : 2.0f;
  }
  float worst = -1;
  size_t worst_i = 0;
  bool nan = false;
  float min_cosine = 2;
  size_t min_cosine_i = SIZE_MAX;
  double sum = 0;
  uint64_t over_warn = 0, over_fail = 0;
  const float w = float(warn), f = float(fail);
  for (size_t i = 0; i < count; ++i) {
    const float e = distance[i];
    largest.add(e);
    sum += double(e);
    over_warn += e > w;
    over_fail += e > f;
    if (e > worst) worst = e, worst_i = i;
    nan |= std::isnan(e);
    float& joint = r.joint_max[c.joint[i]];
    joint = std::max(joint, e);
    if (cosine[i] < min_cosine) min_cosine = cosine[i], min_cosine_i = i;
  }
  r.sum += sum, r.over_warn += over_warn, r.over_fail += over_fail;
  // A NaN is the worst error there is: it must fail whatever the thresholds.
  const double max = nan ? std::numeric_limits<double>::quiet_NaN() : double(std::max(worst, 0.0f));
  direction_max = std::max(direction_max, max);
  if (nan) direction_max = max;
  if (worst >= 0 && !std::isnan(r.figures.max_error) && (nan || max > r.figures.max_error)) {
    r.figures.max_error = max;
    r.worst_side = side, r.worst_vertex = c.vertices[worst_i];
  }
  if (min_cosine_i != SIZE_MAX) {
    const SurfacePoint& s = c.points[min_cosine_i];
    glm::dvec3 n(0);
    for (int k = 0; k < 3; ++k) n += double(s.weight[k]) * glm::dvec3(at(onto_frame.normals, s.vertex[k]));
    const glm::dvec3 m = at(from_frame.normals, c.vertices[min_cosine_i]);
    const double angle = std::atan2(glm::length(glm::cross(m, n)), glm::dot(m, n));
    r.figures.max_normal_degrees = std::max(r.figures.max_normal_degrees, angle * 180.0 / M_PI);
  }
  measure_faces(from_frame, c, point, r);
}

}  // namespace dqskin::diff_detail
