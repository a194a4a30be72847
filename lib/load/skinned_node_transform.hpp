// Skinned mesh nodes whose transform glTF ignores (§3.7.3.1: "only the joint transforms are applied to the
// skinned mesh; the transform of the skinned mesh node MUST be ignored"), and the one notice that says so
// (internal to lib: the loader's Asset::notices and `dqskin lint` share it).
#pragma once

#include "dqskin/asset.hpp"

#include <string>
#include <vector>

namespace dqskin::gltf {

// The nodes with a skin whose own local transform or an ancestor's is not the identity, in node order.
// One walk over the nodes (each node's answer is kept for its children), so a chain of a million skinned
// nodes costs a million steps, not a million squared. `nodes` is a forest (the loader guarantees it).
std::vector<int> skinned_nodes_with_transform(const std::vector<Node>& nodes);

// "3 skinned mesh nodes have a transform (of their own or a parent's); glTF ignores it (§3.7.3.1): node 2
// 'Body', node 5, node 7", naming at most the first five; empty when `moved` is empty.
std::string skinned_node_transform_notice(const std::vector<Node>& nodes, const std::vector<int>& moved);

}  // namespace dqskin::gltf
