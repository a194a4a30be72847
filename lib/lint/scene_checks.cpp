// The scene checks of `dqskin lint`: joints outside the scene that draws their skin, and skinned mesh nodes
// whose transform glTF ignores.
#include "../load/skinned_node_transform.hpp"
#include "lint_checks.hpp"
#include "node_tree.hpp"

#include <algorithm>
#include <map>
#include <set>

namespace dqskin::lint {
namespace {

// A joint that is not in a scene that draws a mesh with its skin. glTF-Validator: NODE_SKIN_NO_SCENE, an
// error. Runtimes pose only the nodes of the scene they show: three.js never updates such a bone's world
// matrix, Babylon links the bone to a node it never created; the mesh then collapses or stays put. (dqskin
// poses every node, so it deforms the file all the same.)
void check_joints_in_scene(const Asset& rig, const NodeTree& tree, Findings& out) {
  // The scenes each root node is listed in (a node is in a scene when its root is one of the scene's).
  std::vector<std::vector<int>> scenes_of(rig.nodes.size());
  for (size_t k = 0; k < rig.scenes.size(); ++k)
    for (int r : rig.scenes[k].roots)
      if (r >= 0 && size_t(r) < rig.nodes.size()) scenes_of[size_t(r)].push_back(int(k));
  for (std::vector<int>& s : scenes_of) {
    std::sort(s.begin(), s.end());
    s.erase(std::unique(s.begin(), s.end()), s.end());
  }
  // Per skin, the scenes that draw it, and the first node that does in each.
  std::vector<std::map<int, int>> drawn_in(rig.skins.size());
  for (size_t n = 0; n < rig.nodes.size(); ++n) {
    const int s = rig.nodes[n].skin;
    if (s < 0 || size_t(s) >= rig.skins.size()) continue;
    for (int k : scenes_of[size_t(tree.root(int(n)))]) drawn_in[size_t(s)].emplace(k, int(n));
  }
  for (size_t s = 0; s < rig.skins.size(); ++s) {
    if (drawn_in[s].empty()) continue;
    const Skin& skin = rig.skins[s];
    std::map<int, int> missing_scene;  // joint root → a scene that draws the skin without it, or -1
    for (size_t j = 0; j < skin.joints.size(); ++j) {
      const int root = tree.root(skin.joints[j]);
      auto it = missing_scene.find(root);
      if (it == missing_scene.end()) {
        int missing = -1;
        for (const auto& scene : drawn_in[s])
          if (!std::binary_search(scenes_of[size_t(root)].begin(), scenes_of[size_t(root)].end(), scene.first)) {
            missing = scene.first;
            break;
          }
        it = missing_scene.emplace(root, missing).first;
      }
      const int scene = it->second;
      if (scene < 0) continue;
      LintExample e;
      e.where = "skin " + std::to_string(s);
      e.joint = static_cast<long long>(j);
      e.value = scene;
      out["joint-not-in-scene"].add(0, e, [&] {
        return "joint " + std::to_string(j) + " (" + node_name(rig, skin.joints[j]) + ", skin " + std::to_string(s) +
               ") is not in scene " + std::to_string(scene) + ", which draws the skin at " +
               node_name(rig, drawn_in[s].at(scene)) + ": runtimes pose only the scene's nodes, so the mesh does not " +
               "follow it";
      });
    }
  }
}

// The loader's notice (skinned_node_transform.hpp) as information: once per file, counting the nodes.
void check_skinned_node_transforms(const Asset& rig, Findings& out) {
  const std::vector<int> moved = gltf::skinned_nodes_with_transform(rig.nodes);
  if (moved.empty()) return;
  const std::string notice = gltf::skinned_node_transform_notice(rig.nodes, moved);
  for (int n : moved) {
    LintExample e;
    e.where = "node " + std::to_string(n);
    out["skinned-node-transform"].add(0, e, [&] { return notice; });
  }
}

}  // namespace

void check_scenes(const Asset& rig, const NodeTree& tree, Findings& out) {
  check_joints_in_scene(rig, tree, out);
  check_skinned_node_transforms(rig, out);
}

}  // namespace dqskin::lint
