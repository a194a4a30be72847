#include "normal_comparison.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace dqskin::diff_detail {

std::vector<uint8_t> smooth_vertices(const DiffSide& side, const PosedSurface& surface) {
  const std::vector<glm::dvec3>& p = surface.positions;
  const std::vector<glm::dvec3>& n = surface.normals;  // zero where the file has none
  std::vector<uint32_t> order(side.vertices);
  std::iota(order.begin(), order.end(), 0u);
  auto before = [&](uint32_t u, uint32_t v) {
    if (p[u].x != p[v].x) return p[u].x < p[v].x;
    if (p[u].y != p[v].y) return p[u].y < p[v].y;
    if (p[u].z != p[v].z) return p[u].z < p[v].z;
    return u < v;
  };
  std::sort(order.begin(), order.end(), before);
  const double agree = std::cos(kSmoothDegrees * M_PI / 180.0);
  std::vector<uint8_t> smooth(side.vertices, 0);
  for (size_t first = 0; first < order.size();) {
    size_t end = first + 1;
    while (end < order.size() && p[order[end]] == p[order[first]]) ++end;
    const glm::dvec3 reference = n[order[first]];
    bool all = glm::length(reference) > 0;
    for (size_t i = first + 1; all && i < end; ++i) {
      const glm::dvec3 m = n[order[i]];
      const double lengths = glm::length(m) * glm::length(reference);
      all = lengths > 0 && glm::dot(m, reference) >= agree * lengths;
    }
    for (size_t i = first; i < end; ++i) smooth[order[i]] = all;
    first = end;
  }
  return smooth;
}

void plan_normal_comparison(const DiffSide& from, std::span<const uint8_t> from_smooth,
                            std::span<const uint8_t> onto_smooth, Correspondence& c) {
  c.smooth.assign(c.vertices.size(), 0);
  std::vector<uint32_t> index_of(from.vertices, UINT32_MAX);
  for (size_t i = 0; i < c.vertices.size(); ++i) {
    index_of[c.vertices[i]] = uint32_t(i);
    bool smooth = from_smooth[c.vertices[i]];
    for (int k = 0; k < 3; ++k) smooth = smooth && (c.points[i].weight[k] == 0 || onto_smooth[c.points[i].vertex[k]]);
    c.smooth[i] = smooth;
  }
  c.faces.clear();
  for (size_t t = 0; t + 2 < from.triangles.size(); t += 3) {
    const uint32_t i0 = index_of[from.triangles[t]], i1 = index_of[from.triangles[t + 1]], i2 = index_of[from.triangles[t + 2]];
    if (i0 == UINT32_MAX || i1 == UINT32_MAX || i2 == UINT32_MAX || i0 == i1 || i1 == i2 || i0 == i2) continue;
    if (c.smooth[i0] && c.smooth[i1] && c.smooth[i2]) continue;
    c.faces.insert(c.faces.end(), {i0, i1, i2});
  }
}

}  // namespace dqskin::diff_detail
