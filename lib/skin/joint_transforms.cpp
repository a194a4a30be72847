// Joint matrices and their dual quaternions, and which meshes a scene draws.
#include "dqskin/error.hpp"
#include "dqskin/skinning.hpp"

namespace dqskin {

JointTransforms joint_transforms(const Skin& skin, const Pose& pose) {
  JointTransforms out;
  const size_t n = skin.joints.size();
  out.matrices.resize(n);
  out.rigid.resize(n);
  out.scale.resize(n);
  for (size_t j = 0; j < n; ++j) {
    // glTF 2.0 §3.7.3.2: jointMatrix = globalTransform(joint) · inverseBindMatrix(joint); the skinned
    // mesh node's own transform is ignored.
    out.matrices[j] = pose.world[size_t(skin.joints[j])] * skin.inverse_bind[j];
    const JointSplit<double> split = split_joint_matrix(out.matrices[j]);
    out.rigid[j] = split.rigid;
    out.scale[j] = split.scale;
    out.any_non_rigid = out.any_non_rigid || !split.is_rigid;
  }
  return out;
}

JointTransforms instance_joint_transforms(const Asset& asset, const MeshInstance& instance, const Pose& pose) {
  if (instance.skin >= 0) return joint_transforms(asset.skins[size_t(instance.skin)], pose);
  const Mat4<double>& world = pose.world[size_t(instance.node)];
  const JointSplit<double> split = split_joint_matrix(world);
  return {{world}, {split.rigid}, {split.scale}, !split.is_rigid};
}

const char* to_string(BlendMode mode) {
  switch (mode) {
    case BlendMode::kLbs: return "lbs";
    case BlendMode::kDqs: return "dqs";
    case BlendMode::kDib: return "dib";
  }
  return "?";
}

bool parse_blend_mode(const std::string& text, BlendMode& mode) {
  for (BlendMode m : {BlendMode::kLbs, BlendMode::kDqs, BlendMode::kDib}) {
    if (text == to_string(m)) {
      mode = m;
      return true;
    }
  }
  return false;
}

int choose_scene(const Asset& asset, int requested) {
  if (requested >= 0) {
    if (size_t(requested) >= asset.scenes.size())
      throw InputError("scene " + std::to_string(requested) + " does not exist (the file has " +
                       std::to_string(asset.scenes.size()) + ")");
    return requested;
  }
  if (asset.default_scene >= 0) return asset.default_scene;
  return asset.scenes.empty() ? -1 : 0;
}

std::vector<MeshInstance> mesh_instances(const Asset& asset, int scene) {
  std::vector<int> roots;
  if (scene >= 0) {
    roots = asset.scenes[size_t(scene)].roots;
  } else {
    for (size_t i = 0; i < asset.nodes.size(); ++i)
      if (asset.nodes[i].parent < 0) roots.push_back(int(i));
  }
  std::vector<MeshInstance> out;
  std::vector<int> stack(roots.rbegin(), roots.rend());
  while (!stack.empty()) {  // depth first, children in order
    const int n = stack.back();
    stack.pop_back();
    const Node& node = asset.nodes[size_t(n)];
    if (node.mesh >= 0) out.push_back({n, node.mesh, node.skin});
    stack.insert(stack.end(), node.children.rbegin(), node.children.rend());
  }
  return out;
}

}  // namespace dqskin
