// The reference crossfade of two clips (docs/DESIGN.md §3.10): blend node-local transforms, then compose.
#include "pose_blend.hpp"

#include <algorithm>
#include <cmath>

namespace dqskin {
namespace {

// Slerp along the shorter arc (the sign of the dot), linear where the arc vanishes: the same rule as the
// keyframe slerp of glTF 2.0 Appendix C (anim/sample.cpp), so a crossfade turns the way a clip would.
Quat<double> shorter_slerp(const Quat<double>& a, Quat<double> b, double t) {
  double d = glm::dot(a, b);
  if (d < 0) b = -b, d = -d;
  if (d > 1 - 1e-12) return glm::normalize(a * (1 - t) + b * t);
  const double angle = std::acos(d), s = std::sin(angle);
  return glm::normalize(a * (std::sin((1 - t) * angle) / s) + b * (std::sin(t * angle) / s));
}

}  // namespace

LocalPose sample_local_pose(const Asset& asset, const Clip* clip, double time) {
  const size_t count = asset.nodes.size();
  LocalPose pose;
  pose.local.resize(count);
  pose.weights.resize(count);
  for (size_t i = 0; i < count; ++i) {
    pose.local[i] = asset.nodes[i].local;
    const int mesh = asset.nodes[i].mesh;
    if (mesh < 0) continue;
    const std::vector<float>& w =
        asset.nodes[i].weights.empty() ? asset.meshes[size_t(mesh)].weights : asset.nodes[i].weights;
    pose.weights[i].assign(w.begin(), w.end());
  }
  if (!clip) return pose;
  for (const Channel& ch : clip->channels) {
    const std::vector<double> v = sample_channel(ch, time);
    LocalTransform& t = pose.local[size_t(ch.node)];
    switch (ch.path) {
      case TargetPath::kTranslation: t.translation = {v[0], v[1], v[2]}; break;
      case TargetPath::kRotation: t.rotation = Quat<double>(v[3], v[0], v[1], v[2]); break;
      case TargetPath::kScale: t.scale = {v[0], v[1], v[2]}; break;
      case TargetPath::kWeights: pose.weights[size_t(ch.node)] = v; break;
    }
  }
  return pose;
}

Pose world_pose(const Asset& asset, const LocalPose& local) {
  // Parent first; the loader guarantees a forest, so following parents terminates.
  const size_t count = asset.nodes.size();
  Pose pose;
  pose.weights = local.weights;
  pose.world.assign(count, Mat4<double>(1.0));
  std::vector<char> done(count, 0);
  std::vector<size_t> chain;
  for (size_t i = 0; i < count; ++i) {
    chain.clear();
    for (int n = int(i); n >= 0 && !done[size_t(n)]; n = asset.nodes[size_t(n)].parent) chain.push_back(size_t(n));
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const int parent = asset.nodes[*it].parent;
      const Mat4<double> m = local.local[*it].to_matrix();
      pose.world[*it] = parent >= 0 ? pose.world[size_t(parent)] * m : m;
      done[*it] = 1;
    }
  }
  return pose;
}

LocalPose blend_local_poses(const LocalPose& a, const LocalPose& b, double w) {
  LocalPose out = a;
  // The ends are the clips themselves, bit for bit (a mixer at weight 0 or 1 plays one clip).
  if (w == 0) return out;
  if (w == 1) return b;
  for (size_t i = 0; i < out.local.size() && i < b.local.size(); ++i) {
    LocalTransform& t = out.local[i];
    const LocalTransform& u = b.local[i];
    if (t.has_matrix) continue;  // not animatable (glTF 2.0 §3.5.3): the same in both poses
    t.translation = (1 - w) * t.translation + w * u.translation;
    t.rotation = shorter_slerp(t.rotation, u.rotation, w);
    t.scale = (1 - w) * t.scale + w * u.scale;
  }
  for (size_t i = 0; i < out.weights.size() && i < b.weights.size(); ++i) {
    std::vector<double>& x = out.weights[i];
    const std::vector<double>& y = b.weights[i];
    for (size_t k = 0; k < std::min(x.size(), y.size()); ++k) x[k] = (1 - w) * x[k] + w * y[k];
  }
  return out;
}

Pose blend_poses(const Asset& asset, const LocalPose& a, const LocalPose& b, double w) {
  return world_pose(asset, blend_local_poses(a, b, w));
}

}  // namespace dqskin
