// The node hierarchy of a file as one depth-first numbering (internal to lib/lint), so that "which root
// does this node hang under" and "is this node an ancestor of that one" cost O(1) each after O(nodes) of
// set-up. Walking parents per joint instead is O(depth) a query: quadratic in a chain of joints, which a
// 200,000-joint chain turned into minutes.
#pragma once

#include "dqskin/asset.hpp"

#include <vector>

namespace dqskin::lint {

class NodeTree {
public:
  // Numbers the forest of `nodes` (the loader guarantees a forest: every node has at most one parent, and
  // `children` mirror `parent`).
  explicit NodeTree(const std::vector<Node>& nodes);

  // The root node above `node` (itself when it has no parent).
  int root(int node) const { return root_[size_t(node)]; }

  // Whether `ancestor` is `node` or one of its ancestors.
  bool is_ancestor_or_self(int ancestor, int node) const {
    return enter_[size_t(ancestor)] <= enter_[size_t(node)] && leave_[size_t(node)] <= leave_[size_t(ancestor)];
  }

private:
  std::vector<int> root_;
  std::vector<size_t> enter_, leave_;  // depth-first order of entering and leaving each node
};

}  // namespace dqskin::lint
