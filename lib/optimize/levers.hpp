// How far a change of one animated value can move the surface (internal to lib/optimize): for every node,
// the surface distance per unit of error in each of its channels, measured at the rest pose in world
// space, through the whole hierarchy, scale included (docs/DESIGN.md §3.12).
#pragma once

#include "dqskin/asset.hpp"
#include "dqskin/skinning.hpp"

#include <vector>

namespace dqskin::optimize_detail {

struct NodeLevers {
  bool moves_vertices = false;  // some vertex depends on this node's transform
  double rotation = 0;     // per radian: the farthest such vertex from the node's origin
  double translation = 0;  // per unit of local translation: the norm of the parent's world 3×3
  double scale = 0;        // per unit of scale: the farthest vertex, in the node's own unscaled frame
  std::vector<double> weights;  // per morph target of the node's mesh: its largest displacement, in world units
};

struct Levers {
  std::vector<NodeLevers> nodes;
  // For every vertex, the nodes its position depends on (the ancestors of its joints, or of its rigid
  // instance's node), as lists of node indices, one list per distinct set. A channel budget is shared
  // among the animated channels of the largest of these sets that a clip animates.
  std::vector<std::vector<int>> dependency_sets;
  double diagonal = 0;  // of the rest pose's bounding box
};

Levers compute_levers(const Asset& asset, const std::vector<MeshInstance>& instances, BlendMode mode);

}  // namespace dqskin::optimize_detail
