#include "dqskin/triangles.hpp"

#include <glm/glm.hpp>

namespace dqskin {

std::vector<uint32_t> triangle_list(const Primitive& prim) {
  const size_t count = prim.indices.empty() ? prim.vertex_count() : prim.indices.size();
  auto vertex = [&](size_t i) { return prim.indices.empty() ? uint32_t(i) : prim.indices[i]; };
  std::vector<uint32_t> out;
  switch (prim.mode) {
    case PrimitiveMode::kTriangles:
      for (size_t i = 0; i + 2 < count; i += 3) out.insert(out.end(), {vertex(i), vertex(i + 1), vertex(i + 2)});
      break;
    case PrimitiveMode::kTriangleStrip:
      for (size_t i = 0; i + 2 < count; ++i) {
        if (i % 2 == 0) out.insert(out.end(), {vertex(i), vertex(i + 1), vertex(i + 2)});
        else out.insert(out.end(), {vertex(i + 1), vertex(i), vertex(i + 2)});
      }
      break;
    case PrimitiveMode::kTriangleFan:
      for (size_t i = 1; i + 1 < count; ++i) out.insert(out.end(), {vertex(0), vertex(i), vertex(i + 1)});
      break;
    default: break;
  }
  return out;
}

std::vector<glm::vec3> smooth_normals(const Primitive& prim) {
  std::vector<glm::dvec3> sum(prim.vertex_count(), glm::dvec3(0));
  const std::vector<uint32_t> tris = triangle_list(prim);
  for (size_t t = 0; t + 2 < tris.size(); t += 3) {
    const glm::dvec3 a(prim.positions[tris[t]]), b(prim.positions[tris[t + 1]]), c(prim.positions[tris[t + 2]]);
    const glm::dvec3 n = glm::cross(b - a, c - a);  // length = 2 × area: area weighting for free
    for (size_t k = 0; k < 3; ++k) sum[tris[t + k]] += n;
  }
  std::vector<glm::vec3> out(sum.size());
  for (size_t i = 0; i < sum.size(); ++i) {
    const double length = glm::length(sum[i]);
    out[i] = length > 0 ? glm::vec3(sum[i] / length) : glm::vec3(0, 0, 1);
  }
  return out;
}

}  // namespace dqskin
