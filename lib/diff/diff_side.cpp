#include "diff_side.hpp"
#include "clip_matching.hpp"

#include "dqskin/animation.hpp"
#include "dqskin/error.hpp"
#include "dqskin/triangles.hpp"

#include <algorithm>
#include <map>

namespace dqskin::diff_detail {
namespace {

// The joint a vertex mostly follows: its largest weight's (the first of equal ones), or the instance's
// own node for rigid instances and weightless vertices, which move with it.
uint32_t joint_of_vertex(const DiffSide& side, const MeshInstance& instance, const Primitive& primitive, size_t v,
                         std::map<std::string, uint32_t>& names, std::vector<std::string>& table) {
  int node = instance.node;
  if (instance.skin >= 0 && primitive.influences > 0) {
    const size_t n = size_t(primitive.influences);
    float best = 0;
    for (size_t k = 0; k < n; ++k)
      if (primitive.weights[v * n + k] > best) {
        best = primitive.weights[v * n + k];
        node = side.asset.skins[size_t(instance.skin)].joints[primitive.joints[v * n + k]];
      }
  }
  const std::string label = node_label(side.asset, node);
  const auto [it, added] = names.emplace(label, uint32_t(table.size()));
  if (added) table.push_back(label);
  return it->second;
}

}  // namespace

DiffSide make_diff_side(Asset asset, BlendMode mode) {
  DiffSide side;
  side.asset = std::move(asset);
  side.instances = mesh_instances(side.asset, choose_scene(side.asset, -1));
  std::map<std::string, uint32_t> names;
  for (const MeshInstance& instance : side.instances)
    for (const Primitive& primitive : side.asset.meshes[size_t(instance.mesh)].primitives) {
      const size_t first = side.vertices;
      side.first_vertex.push_back(first);
      side.primitive_size.push_back(primitive.vertex_count());
      side.file_normals.push_back(!primitive.normals.empty() && !primitive.normals_generated);
      side.vertices += primitive.vertex_count();
      const std::vector<uint32_t> triangles = triangle_list(primitive);
      for (uint32_t i : triangles) side.triangles.push_back(uint32_t(first + i));
      side.on_surface.resize(side.vertices, triangles.empty() ? 0 : 1);
      for (size_t v = 0; v < primitive.vertex_count(); ++v)
        side.joint.push_back(joint_of_vertex(side, instance, primitive, v, names, side.joint_names));
    }
  if (side.triangles.empty()) throw InputError("the scene has no triangles to compare");
  if (side.vertices > UINT32_MAX) throw InputError("the scene has more than 2^32 vertices");

  const DeformedFrame rest = deform_frame(side.asset, side.instances, sample_pose(side.asset, nullptr, 0), mode);
  side.rest.reserve(side.vertices);
  for (size_t i = 0; i < rest.primitives.size(); ++i) {
    const DeformedPrimitive& p = rest.primitives[i];
    side.rest.insert(side.rest.end(), p.positions.begin(), p.positions.end());
    if (!side.file_normals[i])
      side.rest_normals.resize(side.rest.size(), glm::dvec3(0));
    else
      side.rest_normals.insert(side.rest_normals.end(), p.normals.begin(), p.normals.end());
  }
  return side;
}

void gather_frame(const DiffSide& side, const DeformedBatch& batch, size_t frame, SideFrame& out) {
  out.positions.resize(3 * side.vertices);
  out.normals.resize(3 * side.vertices);
  for (size_t p = 0; p < batch.primitives.size(); ++p) {
    const DeformedBatch::Primitive& prim = batch.primitives[p];
    const size_t n = 3 * prim.vertices, at = 3 * side.first_vertex[p];
    std::copy_n(prim.positions.begin() + std::ptrdiff_t(frame * n), n, out.positions.begin() + std::ptrdiff_t(at));
    if (side.file_normals[p])
      std::copy_n(prim.normals.begin() + std::ptrdiff_t(frame * n), n, out.normals.begin() + std::ptrdiff_t(at));
    else
      std::fill_n(out.normals.begin() + std::ptrdiff_t(at), n, 0.0f);
  }
}

}  // namespace dqskin::diff_detail
