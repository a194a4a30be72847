#include "closed_volume.hpp"

#include "dqskin/triangles.hpp"

#include <algorithm>
#include <map>
#include <tuple>

namespace dqskin::report_detail {

bool is_closed(std::span<const std::array<uint32_t, 3>> triangles) {
  if (triangles.empty()) return false;
  // Each undirected edge with the direction the triangle runs it in: a closed, consistently wound surface
  // has every edge twice, once each way. An inconsistently wound one has no meaningful signed volume.
  std::vector<std::tuple<uint32_t, uint32_t, bool>> edges;
  edges.reserve(triangles.size() * 3);
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = t[size_t(k)], b = t[size_t((k + 1) % 3)];
      if (a == b) return false;  // a degenerate triangle: its "edge" is no edge of a surface
      edges.emplace_back(std::min(a, b), std::max(a, b), a < b);
    }
  std::sort(edges.begin(), edges.end());
  for (size_t i = 0; i < edges.size(); i += 2) {
    if (i + 1 >= edges.size()) return false;
    const auto& [a0, b0, forward0] = edges[i];
    const auto& [a1, b1, forward1] = edges[i + 1];
    if (a0 != a1 || b0 != b1 || forward0 == forward1) return false;
    if (i + 2 < edges.size() && std::get<0>(edges[i + 2]) == a0 && std::get<1>(edges[i + 2]) == b0) return false;
  }
  return true;
}

std::vector<BatchTriangle> closed_triangles(const Asset& asset, const std::vector<MeshInstance>& instances,
                                            const SkinRegions& regions) {
  std::vector<BatchTriangle> out;
  for (size_t i = 0; i < instances.size(); ++i) {
    std::vector<BatchTriangle> mine;
    std::vector<std::array<uint32_t, 3>> welded;
    std::map<std::array<float, 3>, uint32_t> ids;  // bind position → welded vertex id
    bool skinned = false;
    for (size_t b = 0; b < regions.primitives.size(); ++b) {
      const BatchPrimitive& bp = regions.primitives[b];
      if (bp.instance != i) continue;
      const Primitive& primitive = asset.meshes[size_t(instances[i].mesh)].primitives[bp.primitive];
      if (primitive.mode < PrimitiveMode::kTriangles) continue;  // points and lines bound no volume
      skinned = skinned || bp.skin >= 0;
      std::vector<uint32_t> id(primitive.vertex_count());
      for (size_t v = 0; v < id.size(); ++v) {
        const glm::vec3 p = primitive.positions[v];
        id[v] = ids.try_emplace({p.x, p.y, p.z}, uint32_t(ids.size())).first->second;
      }
      const std::vector<uint32_t> list = triangle_list(primitive);
      for (size_t t = 0; t + 2 < list.size(); t += 3) {
        mine.push_back({uint32_t(b), {list[t], list[t + 1], list[t + 2]}});
        welded.push_back({id[list[t]], id[list[t + 1]], id[list[t + 2]]});
      }
    }
    if (skinned && is_closed(welded)) out.insert(out.end(), mine.begin(), mine.end());
  }
  return out;
}

double signed_volume(std::span<const BatchTriangle> triangles, const FrameView& frame) {
  double volume = 0;
  for (const BatchTriangle& t : triangles) {
    const std::span<const float> p = frame.primitives[t.primitive].positions;
    auto at = [&](uint32_t v) { return glm::dvec3(p[3 * v], p[3 * v + 1], p[3 * v + 2]); };
    volume += glm::dot(at(t.vertex[0]), glm::cross(at(t.vertex[1]), at(t.vertex[2])));
  }
  return volume / 6.0;
}

}  // namespace dqskin::report_detail
