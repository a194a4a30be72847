#include "skinned_node_transform.hpp"

#include <cstdint>

namespace dqskin::gltf {

std::vector<int> skinned_nodes_with_transform(const std::vector<Node>& nodes) {
  // moved[n]: 1 when n or an ancestor has a transform, 0 when none has, -1 not yet known. A node's answer
  // is its parent's or its own; the walk up from each node stops at the first known one and fills in the
  // nodes it passed on the way back, so every node is settled once.
  std::vector<int8_t> moved(nodes.size(), -1);
  std::vector<size_t> path;
  for (size_t start = 0; start < nodes.size(); ++start) {
    if (nodes[start].skin < 0) continue;
    size_t n = start;
    while (moved[n] < 0) {
      path.push_back(n);
      if (nodes[n].local.to_matrix() != Mat4<double>(1.0)) {
        moved[n] = 1;
        path.pop_back();
        break;
      }
      if (nodes[n].parent < 0) {
        moved[n] = 0;
        path.pop_back();
        break;
      }
      n = size_t(nodes[n].parent);
    }
    for (auto p = path.rbegin(); p != path.rend(); ++p) moved[*p] = moved[n];
    path.clear();
  }
  std::vector<int> out;
  for (size_t n = 0; n < nodes.size(); ++n)
    if (nodes[n].skin >= 0 && moved[n] == 1) out.push_back(int(n));
  return out;
}

std::string skinned_node_transform_notice(const std::vector<Node>& nodes, const std::vector<int>& moved) {
  if (moved.empty()) return {};
  constexpr size_t kNamed = 5;
  std::string s = moved.size() == 1 ? "1 skinned mesh node has a transform (its own or a parent's)"
                                    : std::to_string(moved.size()) +
                                          " skinned mesh nodes have a transform (of their own or a parent's)";
  s += "; glTF ignores it (§3.7.3.1): ";
  for (size_t i = 0; i < moved.size() && i < kNamed; ++i) {
    const Node& node = nodes[size_t(moved[i])];
    s += (i ? ", node " : "node ") + std::to_string(moved[i]);
    if (!node.name.empty()) s += " '" + node.name + "'";
  }
  if (moved.size() > kNamed) s += ", …";
  return s;
}

}  // namespace dqskin::gltf
