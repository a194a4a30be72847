#include "correspondence.hpp"
#include "../base/parallel_for.hpp"

#include "dqskin/error.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <limits>
#include <string>

namespace dqskin::diff_detail {

Box bounding_box(const DiffSide& side, const PosedSurface& surface) {
  Box box{glm::dvec3(std::numeric_limits<double>::infinity()), glm::dvec3(-std::numeric_limits<double>::infinity())};
  for (size_t v = 0; v < side.vertices; ++v)
    if (side.on_surface[v]) box.low = glm::min(box.low, surface.positions[v]), box.high = glm::max(box.high, surface.positions[v]);
  return box;
}

bool same_vertices(const DiffSide& a, const PosedSurface& pa, const DiffSide& b, const PosedSurface& pb, double tolerance) {
  if (a.primitive_size != b.primitive_size) return false;
  for (size_t v = 0; v < a.vertices; ++v)
    if (glm::length(pa.positions[v] - pb.positions[v]) > tolerance) return false;
  return true;
}

Correspondence identity(const DiffSide& side) {
  Correspondence c;
  for (size_t v = 0; v < side.vertices; ++v) {
    if (!side.on_surface[v]) continue;
    c.vertices.push_back(uint32_t(v));
    SurfacePoint p;
    p.vertex[0] = p.vertex[1] = p.vertex[2] = uint32_t(v);
    c.points.push_back(p);
  }
  return c;
}

Correspondence closest_points(const DiffSide& from, const PosedSurface& from_pose, const DiffSide& onto,
                              const PosedSurface& onto_pose, const char* onto_name, unsigned threads) {
  const SurfaceIndex index(onto_pose.positions, onto.triangles, onto_pose.normals);
  if (index.empty()) throw InputError(std::string(onto_name) + "'s triangles all have zero area");
  Correspondence c;
  for (size_t v = 0; v < from.vertices; ++v)
    if (from.on_surface[v]) c.vertices.push_back(uint32_t(v));
  c.points.resize(c.vertices.size());
  constexpr size_t kBlock = 1024;
  concurrency::parallel_for((c.vertices.size() + kBlock - 1) / kBlock, threads, [&](size_t block) {
    const size_t end = std::min(c.vertices.size(), (block + 1) * kBlock);
    for (size_t i = block * kBlock; i < end; ++i)
      c.points[i] = index.closest(from_pose.positions[c.vertices[i]], from_pose.normals[c.vertices[i]]);
  });
  for (const SurfacePoint& p : c.points) c.max_rest_distance = std::max(c.max_rest_distance, double(p.distance));
  return c;
}

}  // namespace dqskin::diff_detail
