#include "motion_nodes.hpp"

#include "dqskin/error.hpp"

#include <algorithm>
#include <limits>

namespace dqskin::bake_detail {
namespace {

bool is_ancestor_or_self(const Asset& asset, int ancestor, int node) {
  for (int n = node; n >= 0; n = asset.nodes[size_t(n)].parent)
    if (n == ancestor) return true;
  return false;
}

// The first joint of `skin` that `root` does not carry, or -1.
int joint_outside(const Asset& asset, const Skin& skin, int root) {
  for (int j : skin.joints)
    if (!is_ancestor_or_self(asset, root, j)) return j;
  return -1;
}

size_t depth(const Asset& asset, int node) {
  size_t d = 0;
  for (int n = asset.nodes[size_t(node)].parent; n >= 0; n = asset.nodes[size_t(n)].parent) ++d;
  return d;
}

std::string describe(const Asset& asset, int node) {
  const std::string& name = asset.nodes[size_t(node)].name;
  return (name.empty() ? "node" : "'" + name + "'") + " (#" + std::to_string(node) + ")";
}

}  // namespace

int find_named_node(const Asset& asset, const std::string& name, const std::string& flag) {
  if (name.size() > 1 && name[0] == '#' && name.size() < 12 &&
      std::all_of(name.begin() + 1, name.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    const size_t index = std::stoul(name.substr(1));
    if (index >= asset.nodes.size())
      throw InputError(flag + ": there is no node " + name + " (the file has " + std::to_string(asset.nodes.size()) +
                       " nodes)");
    return int(index);
  }
  std::vector<int> found;
  for (size_t n = 0; n < asset.nodes.size(); ++n)
    if (asset.nodes[n].name == name) found.push_back(int(n));
  if (found.empty()) throw InputError(flag + ": no node is named '" + name + "'");
  if (found.size() > 1) {
    std::string which;
    for (int n : found) which += (which.empty() ? "#" : ", #") + std::to_string(n);
    throw InputError(flag + ": " + std::to_string(found.size()) + " nodes are named '" + name + "' (" + which +
                     "); name one as #N");
  }
  return found.front();
}

int choose_root(const InputPlan& input, const std::string& root_joint) {
  const Asset& asset = *input.asset;
  int root = -1;
  std::string flag = "--root-joint";
  if (!root_joint.empty()) {
    root = find_named_node(asset, root_joint, flag);
  } else {
    flag = "--root-motion";
    if (input.skins.empty()) throw InputError("--root-motion: the scene has no skinned mesh; name the root with --root-joint");
    const Skin& skin = asset.skins[size_t(input.skins.front())];
    if (skin.skeleton >= 0 && size_t(skin.skeleton) < asset.nodes.size() && joint_outside(asset, skin, skin.skeleton) < 0) {
      root = skin.skeleton;
    } else {
      size_t best = std::numeric_limits<size_t>::max();
      for (int j : skin.joints)
        if (joint_outside(asset, skin, j) < 0 && depth(asset, j) < best) root = j, best = depth(asset, j);
    }
    if (root < 0)
      throw InputError("--root-motion: no joint of skin " + std::to_string(input.skins.front()) +
                       " is an ancestor of all its joints; name the root with --root-joint");
  }
  for (int s : input.skins)
    if (const int j = joint_outside(asset, asset.skins[size_t(s)], root); j >= 0)
      throw InputError(flag + ": the root " + describe(asset, root) + " is not an ancestor of joint " + describe(asset, j) +
                       " of skin " + std::to_string(s) + ", so its motion is not the skin's");
  return root;
}

MotionNodes find_motion_nodes(const InputPlan& input, const MotionOptions& options) {
  MotionNodes nodes;
  for (const std::string& name : options.sockets) nodes.sockets.push_back(find_named_node(*input.asset, name, "--sockets"));
  if (options.in_place) nodes.root = choose_root(input, options.root_joint);
  return nodes;
}

void set_in_place(InputPlan& input, const MotionNodes& nodes) {
  for (Clip& clip : input.asset->clips) clip.in_place_root = nodes.root;
}

}  // namespace dqskin::bake_detail
