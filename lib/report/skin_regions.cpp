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

namespace {

// A skin's joint tree, made once per skin: for each joint its parent joint (the nearest ancestor node that
// is a joint of the skin) and its bind position. Linear in nodes and joints, so that a skin of many
// thousands of joints costs no more than its size.
struct SkinTree {
  std::vector<int> parent;              // per joint, -1 for none
  std::vector<glm::dvec3> bind;         // per joint: inverse(IBM) · origin
  std::vector<glm::dvec3> child_axis;   // per joint: towards its first child joint, or zero
};

SkinTree skin_tree(const Asset& asset, const Skin& skin) {
  std::vector<int> joint_of_node(asset.nodes.size(), -1);
  for (size_t j = 0; j < skin.joints.size(); ++j)
    if (joint_of_node[size_t(skin.joints[j])] < 0) joint_of_node[size_t(skin.joints[j])] = int(j);
  // nearest[n]: the joint at or above node n, memoized along each walk up (-2: not known yet).
  std::vector<int> nearest(asset.nodes.size(), -2);
  std::vector<int> path;
  auto joint_at_or_above = [&](int node) {
    path.clear();
    int n = node, found = -1;
    for (; n >= 0; n = asset.nodes[size_t(n)].parent) {
      if (nearest[size_t(n)] != -2) {
        found = nearest[size_t(n)];
        break;
      }
      if (joint_of_node[size_t(n)] >= 0) {
        found = joint_of_node[size_t(n)];
        nearest[size_t(n)] = found;
        break;
      }
      path.push_back(n);
    }
    for (int m : path) nearest[size_t(m)] = found;
    return found;
  };
  SkinTree tree;
  tree.parent.resize(skin.joints.size(), -1);
  tree.bind.resize(skin.joints.size());
  tree.child_axis.assign(skin.joints.size(), glm::dvec3(0.0));
  for (size_t j = 0; j < skin.joints.size(); ++j) {
    const int parent_node = asset.nodes[size_t(skin.joints[j])].parent;
    tree.parent[j] = parent_node < 0 ? -1 : joint_at_or_above(parent_node);
    tree.bind[j] = glm::dvec3(glm::inverse(skin.inverse_bind[j]) * glm::dvec4(0, 0, 0, 1));
  }
  for (size_t k = 0; k < skin.joints.size(); ++k) {
    const int parent = tree.parent[k];
    if (parent < 0 || tree.child_axis[size_t(parent)] != glm::dvec3(0.0)) continue;
    tree.child_axis[size_t(parent)] = unit_or_zero(tree.bind[k] - tree.bind[size_t(parent)]);
  }
  return tree;
}

}  // namespace

SkinRegions skin_regions(const Asset& asset, const std::vector<MeshInstance>& instances) {
  SkinRegions out;
  // (skin, joint) → index into out.joints, made as regions are found, ordered at the end.
  std::map<std::pair<int, int>, JointRegion> found;
  std::map<int, SkinTree> trees;

  auto region = [&](int skin_index, int joint) -> JointRegion& {
    auto [it, made] = found.try_emplace({skin_index, joint});
    JointRegion& r = it->second;
    if (!made) return r;
    const Skin& skin = asset.skins[size_t(skin_index)];
    auto tree_at = trees.find(skin_index);
    if (tree_at == trees.end()) tree_at = trees.emplace(skin_index, skin_tree(asset, skin)).first;
    const SkinTree& tree = tree_at->second;
    r.skin = skin_index;
    r.joint = joint;
    r.node = skin.joints[size_t(joint)];
    r.name = asset.nodes[size_t(r.node)].name;
    if (r.name.empty()) {
      r.name = "node ";
      r.name += std::to_string(r.node);
    }
    r.parent = tree.parent[size_t(joint)];
    r.bind_position = tree.bind[size_t(joint)];
    if (r.parent >= 0) r.section_axis = unit_or_zero(r.bind_position - tree.bind[size_t(r.parent)]);
    // The twist axis runs along the bone the joint carries: towards its first child joint (the first of
    // the skin's joints, in skin order, whose parent joint it is), else the bone it ends.
    r.twist_axis = tree.child_axis[size_t(joint)] != glm::dvec3(0.0) ? tree.child_axis[size_t(joint)] : r.section_axis;
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
