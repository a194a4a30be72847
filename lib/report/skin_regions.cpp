#include "skin_regions.hpp"

#include <algorithm>
#include <map>

namespace dqskin::report_detail {
namespace {

glm::dvec3 unit_or_zero(const glm::dvec3& v) {
  const double length = glm::length(v);
  return length > 1e-12 ? v / length : glm::dvec3(0.0);
}

}  // namespace

std::vector<Influence> vertex_influences(const Primitive& primitive, size_t v) {
  std::vector<Influence> out;
  const size_t n = size_t(primitive.influences);
  double sum = 0;
  for (size_t k = 0; k < n; ++k) sum += double(primitive.weights[v * n + k]);
  if (!(sum > 0)) return out;
  for (size_t k = 0; k < n; ++k) {
    const double w = double(primitive.weights[v * n + k]) / sum;
    if (!(w > 0)) continue;
    const int joint = primitive.joints[v * n + k];
    auto same = std::find_if(out.begin(), out.end(), [&](const Influence& i) { return i.joint == joint; });
    if (same != out.end()) same->weight += w;
    else out.push_back({joint, w});
  }
  return out;
}

SkinRegions skin_regions(const Asset& asset, const std::vector<MeshInstance>& instances) {
  SkinRegions out;
  // (skin, joint) → index into out.joints, made as regions are found, ordered at the end.
  std::map<std::pair<int, int>, JointRegion> found;

  auto region = [&](int skin_index, int joint) -> JointRegion& {
    auto [it, made] = found.try_emplace({skin_index, joint});
    JointRegion& r = it->second;
    if (!made) return r;
    const Skin& skin = asset.skins[size_t(skin_index)];
    r.skin = skin_index;
    r.joint = joint;
    r.node = skin.joints[size_t(joint)];
    r.name = asset.nodes[size_t(r.node)].name;
    if (r.name.empty()) {
      r.name = "node ";
      r.name += std::to_string(r.node);
    }
    auto joint_of_node = [&](int node) {
      const auto at = std::find(skin.joints.begin(), skin.joints.end(), node);
      return at == skin.joints.end() ? -1 : int(at - skin.joints.begin());
    };
    auto bind_of = [&](int j) { return glm::dvec3(glm::inverse(skin.inverse_bind[size_t(j)]) * glm::dvec4(0, 0, 0, 1)); };
    for (int n = asset.nodes[size_t(r.node)].parent; n >= 0 && r.parent < 0; n = asset.nodes[size_t(n)].parent)
      r.parent = joint_of_node(n);
    r.bind_position = bind_of(joint);
    if (r.parent >= 0) r.section_axis = unit_or_zero(r.bind_position - bind_of(r.parent));
    // The twist axis runs along the bone the joint carries: towards its first child joint (the first of
    // the skin's joints, in skin order, whose parent joint it is), else the bone it ends.
    r.twist_axis = r.section_axis;
    for (size_t k = 0; k < skin.joints.size(); ++k) {
      int parent = -1;
      for (int n = asset.nodes[size_t(skin.joints[k])].parent; n >= 0 && parent < 0; n = asset.nodes[size_t(n)].parent)
        parent = joint_of_node(n);
      if (parent != joint) continue;
      const glm::dvec3 axis = unit_or_zero(bind_of(int(k)) - r.bind_position);
      if (axis != glm::dvec3(0.0)) {
        r.twist_axis = axis;
        break;
      }
    }
    return r;
  };

  for (size_t i = 0; i < instances.size(); ++i) {
    const MeshInstance& instance = instances[i];
    const Mesh& mesh = asset.meshes[size_t(instance.mesh)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const Primitive& primitive = mesh.primitives[p];
      const uint32_t batch_index = uint32_t(out.primitives.size());
      const bool skinned = instance.skin >= 0 && primitive.influences > 0;
      out.primitives.push_back({i, instance.mesh, p, skinned ? instance.skin : -1, primitive.vertex_count()});
      out.vertices += primitive.vertex_count();
      if (!skinned) continue;
      out.skinned_vertices += primitive.vertex_count();
      for (size_t v = 0; v < primitive.vertex_count(); ++v) {
        const std::vector<Influence> influences = vertex_influences(primitive, v);
        if (influences.empty()) continue;
        out.max_influences = std::max(out.max_influences, int(influences.size()));
        const Influence heaviest = *std::max_element(influences.begin(), influences.end(),
                                                     [](const Influence& a, const Influence& b) { return a.weight < b.weight; });
        const VertexRef ref{batch_index, uint32_t(v)};
        region(instance.skin, heaviest.joint).vertices.push_back(ref);
        // Blend zones: this vertex is in the zone of every influence j whose parent joint also weighs.
        for (const Influence& a : influences) {
          if (a.weight < kZoneWeight) continue;
          JointRegion& r = region(instance.skin, a.joint);
          if (r.parent < 0 || r.section_axis == glm::dvec3(0.0)) continue;
          for (const Influence& b : influences)
            if (b.joint == r.parent && b.weight >= kZoneWeight) {
              const glm::dvec3 bind(primitive.positions[v]);
              r.zone.push_back({ref, bind, glm::dot(bind - r.bind_position, r.section_axis)});
            }
        }
      }
    }
  }
  for (auto& entry : found)
    if (!entry.second.vertices.empty()) out.joints.push_back(std::move(entry.second));
  return out;
}

}  // namespace dqskin::report_detail
