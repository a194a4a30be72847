#include "frame_measure.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dqskin::diff_detail {

void measure(const SideFrame& from_frame, const SideFrame& onto_frame, const Correspondence& c, double warn, double fail,
             char side, FrameResult& r, LargestErrors& largest, double& direction_max) {
  const float* P = onto_frame.positions.data();
  const float* N = onto_frame.normals.data();
  const float* A = from_frame.positions.data();
  const float* M = from_frame.normals.data();
  // Two passes: the distances and normal cosines without a branch, so that the fetches of many samples
  // are in flight at once; then the reductions over them.
  const size_t count = c.vertices.size();
  thread_local std::vector<float> distance, cosine;
  distance.resize(count);
  cosine.resize(count);
  for (size_t i = 0; i < count; ++i) {
    const size_t a = 3 * size_t(c.vertices[i]);
    const SurfacePoint& s = c.points[i];
    float p[3] = {0, 0, 0}, n[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      const size_t o = 3 * size_t(s.vertex[k]);
      for (int j = 0; j < 3; ++j) p[j] += s.weight[k] * P[o + size_t(j)], n[j] += s.weight[k] * N[o + size_t(j)];
    }
    const float dx = A[a] - p[0], dy = A[a + 1] - p[1], dz = A[a + 2] - p[2];
    distance[i] = std::sqrt(dx * dx + dy * dy + dz * dz);
    const float mm = M[a] * M[a] + M[a + 1] * M[a + 1] + M[a + 2] * M[a + 2];
    const float nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    const float dot = M[a] * n[0] + M[a + 1] * n[1] + M[a + 2] * n[2];
    // 2 (no angle) where either normal is missing: never the smallest cosine.
    cosine[i] = mm > 0 && nn > 1e-12f ? dot / std::sqrt(mm * nn) : 2.0f;
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
}

}  // namespace dqskin::diff_detail
