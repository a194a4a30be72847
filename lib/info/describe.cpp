// What `dqskin info` reports, computed from the Asset.
#include "dqskin/info.hpp"

#include "dqskin/animation.hpp"
#include "dqskin/skinning.hpp"

#include <algorithm>
#include <set>

namespace dqskin {
namespace {

size_t triangle_count(const Primitive& p) {
  const size_t n = p.indices.empty() ? p.vertex_count() : p.indices.size();
  switch (p.mode) {
    case PrimitiveMode::kTriangles: return n / 3;
    case PrimitiveMode::kTriangleStrip:
    case PrimitiveMode::kTriangleFan: return n >= 3 ? n - 2 : 0;
    default: return 0;
  }
}

int max_influences(const Primitive& p) {
  int best = 0;
  for (size_t v = 0; v < p.vertex_count(); ++v) {
    int count = 0;
    for (size_t k = 0; k < size_t(p.influences); ++k) count += p.weights[v * size_t(p.influences) + k] > 0;
    best = std::max(best, count);
  }
  return best;
}

}  // namespace

AssetFacts describe(const Asset& asset) {
  AssetFacts f;
  f.scenes = asset.scenes.size();
  f.default_scene = asset.default_scene;

  std::set<int> accessors;
  for (const Mesh& mesh : asset.meshes)
    for (const Primitive& p : mesh.primitives)
      if (accessors.insert(p.position_accessor).second) f.vertices += p.vertex_count();

  std::set<int> joints;
  for (const Skin& s : asset.skins) joints.insert(s.joints.begin(), s.joints.end());
  f.joint_nodes = joints.size();

  for (size_t i = 0; i < asset.nodes.size(); ++i) {
    const Node& node = asset.nodes[i];
    if (node.skin < 0) continue;
    const Mesh& mesh = asset.meshes[size_t(node.mesh)];
    SkinnedMeshFacts m;
    m.node = int(i);
    m.mesh = node.mesh;
    m.skin = node.skin;
    m.name = !node.name.empty() ? node.name : mesh.name;
    std::set<int> seen;
    for (const Primitive& p : mesh.primitives) {
      if (seen.insert(p.position_accessor).second) m.vertices += p.vertex_count();
      m.triangles += triangle_count(p);
      m.max_influences = std::max(m.max_influences, max_influences(p));
      m.influence_sets = std::max(m.influence_sets, p.influences / 4);
    }
    f.skinned_meshes.push_back(m);
  }

  // Non-rigid joints: at rest, and at every key time of every clip. Each pose is sampled once and
  // checked against every skin still rigid so far (RecursiveSkeletons has 84 skins on one skeleton).
  const Pose rest = sample_pose(asset, nullptr, 0);
  for (const Skin& skin : asset.skins)
    f.skins.push_back({skin.name, skin.joints.size(), joint_transforms(skin, rest).any_non_rigid, false});
  size_t still_rigid = asset.skins.size();
  FrameSpec keys;
  keys.keys = true;
  for (const Clip& clip : asset.clips) {
    for (double t : frame_times(clip, keys)) {
      if (still_rigid == 0) break;
      const Pose pose = sample_pose(asset, &clip, t);
      for (size_t i = 0; i < asset.skins.size(); ++i) {
        if (f.skins[i].non_rigid_in_animation || !joint_transforms(asset.skins[i], pose).any_non_rigid) continue;
        f.skins[i].non_rigid_in_animation = true;
        --still_rigid;
      }
    }
  }

  for (const Clip& clip : asset.clips) {
    ClipFacts c;
    c.name = clip.name;
    c.duration = clip.last_key;
    c.first_key = clip.first_key;
    c.channels = clip.channels.size();
    std::set<std::string> kinds;
    for (const Channel& ch : clip.channels)
      kinds.insert(ch.interpolation == Interpolation::kStep     ? "STEP"
                   : ch.interpolation == Interpolation::kLinear ? "LINEAR"
                                                                : "CUBICSPLINE");
    c.interpolations.assign(kinds.begin(), kinds.end());
    f.clips.push_back(c);
  }

  for (size_t m = 0; m < asset.meshes.size(); ++m) {
    const size_t targets = asset.meshes[m].primitives.front().targets.size();
    if (targets) f.morph_targets.push_back({int(m), asset.meshes[m].name, targets});
  }

  f.cannot_deform = asset.cannot_deform;
  f.warnings = asset.warnings;
  // `info` describes everything, so the notices (what glTF defines and dqskin follows) are among its warnings.
  f.warnings.insert(f.warnings.end(), asset.notices.begin(), asset.notices.end());
  const std::vector<std::string> w = weight_warnings(asset);
  f.warnings.insert(f.warnings.end(), w.begin(), w.end());
  return f;
}

}  // namespace dqskin
