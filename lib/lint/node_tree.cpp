// One iterative depth-first walk over the node forest (node_tree.hpp); iterative, so that a deep chain
// cannot overflow the stack.
#include "node_tree.hpp"

#include <utility>

namespace dqskin::lint {

NodeTree::NodeTree(const std::vector<Node>& nodes)
    : root_(nodes.size(), -1), enter_(nodes.size(), 0), leave_(nodes.size(), 0) {
  size_t clock = 0;
  std::vector<std::pair<int, size_t>> stack;  // (node, next child to visit)
  for (size_t r = 0; r < nodes.size(); ++r) {
    if (nodes[r].parent >= 0) continue;
    root_[r] = int(r);
    enter_[r] = clock++;
    stack.emplace_back(int(r), 0);
    while (!stack.empty()) {
      auto& [node, next] = stack.back();
      const std::vector<int>& children = nodes[size_t(node)].children;
      if (next < children.size()) {
        const int child = children[next++];
        root_[size_t(child)] = int(r);
        enter_[size_t(child)] = clock++;
        stack.emplace_back(child, 0);
      } else {
        leave_[size_t(node)] = clock++;
        stack.pop_back();
      }
    }
  }
}

}  // namespace dqskin::lint
