// The per-joint checks of `dqskin lint`: the joints' hierarchy (glTF 2.0 §3.7.3.1 and the skin schema:
// joints share a common root, and `skeleton` is that root or one of its ancestors), inverse bind matrices
// against the rest pose, and the scale and shear of joint matrices world · inverseBind (DESIGN.md
// "Non-rigid joints": uniform scale survives DQS with the two-phase rule; shear and non-uniform scale need
// it, and plain DQS runtimes distort them).
#include "lint_checks.hpp"
#include "node_tree.hpp"

#include "dqskin/animation.hpp"
#include "dqskin/dual_quat.hpp"
#include "dqskin/job.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace dqskin::lint {
namespace {

std::string node_name(const Asset& a, int node) {
  std::string s = "node " + std::to_string(node);
  if (!a.nodes[size_t(node)].name.empty()) s += " '" + a.nodes[size_t(node)].name + "'";
  return s;
}

std::string skin_name(size_t s) { return "skin " + std::to_string(s); }

LintExample joint_example(std::string where, size_t joint, double value) {
  LintExample e;
  e.where = std::move(where);
  e.joint = static_cast<long long>(joint);
  e.value = value;
  return e;
}

void check_roots(const Asset& a, const NodeTree& tree, size_t s, Findings& out) {
  const Skin& skin = a.skins[s];
  const int root = tree.root(skin.joints.front());
  for (size_t j = 0; j < skin.joints.size(); ++j) {
    const int r = tree.root(skin.joints[j]);
    if (r != root)
      out["no-common-root"].add(0, joint_example(skin_name(s), j, r), [&] {
        return "joint " + std::to_string(j) + " (" + node_name(a, skin.joints[j]) + ") hangs under root " +
               node_name(a, r) + ", joint 0 under " + node_name(a, root) + " (" + skin_name(s) + ")";
      });
    if (skin.skeleton >= 0 && !tree.is_ancestor_or_self(skin.skeleton, skin.joints[j]))
      out["skeleton-not-root"].add(0, joint_example(skin_name(s), j, skin.skeleton), [&] {
        return "skeleton " + node_name(a, skin.skeleton) + " is not an ancestor of joint " + std::to_string(j) + " (" +
               node_name(a, skin.joints[j]) + ") of " + skin_name(s);
      });
  }
}

// Largest |S − I| entry of a 3×3 S, and of S − s I with s its mean diagonal (how far from uniform).
struct ScaleMeasure {
  double off_identity = 0;
  double off_uniform = 0;
};
ScaleMeasure measure(const Mat3<double>& S) {
  const double s = (S[0][0] + S[1][1] + S[2][2]) / 3;
  ScaleMeasure m;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) {
      const double id = c == r ? 1.0 : 0.0;
      m.off_identity = std::max(m.off_identity, std::abs(S[c][r] - id));
      m.off_uniform = std::max(m.off_uniform, std::abs(S[c][r] - s * id));
    }
  return m;
}

// The size of the skeleton at rest: diagonal of its joints' positions, at least 1 unit, so that a
// translation error of a centimetre model and of a kilometre one are judged alike.
double skeleton_size(const Skin& skin, const Pose& rest) {
  Vec3<double> lo(0.0), hi(0.0);
  for (size_t j = 0; j < skin.joints.size(); ++j) {
    const Vec3<double> p(rest.world[size_t(skin.joints[j])][3]);
    lo = j == 0 ? p : glm::min(lo, p);
    hi = j == 0 ? p : glm::max(hi, p);
  }
  return std::max(1.0, glm::length(hi - lo));
}

// Each skin's bind space placed in the world at rest: the world matrix of the first node that draws a mesh
// with the skin, or the identity when none does. At the bind pose every joint matrix world · inverseBind
// equals it (the mesh then appears where it was bound: exporters put the armature's own transform, such as
// a Z-up to Y-up turn, into both), so a joint whose matrix differs was bound elsewhere than the file's rest
// pose puts it. One pass over the nodes for every skin (a pass per skin is skins × nodes).
std::vector<Mat4<double>> bind_placements(const Asset& a, const Pose& rest) {
  std::vector<Mat4<double>> placement(a.skins.size(), Mat4<double>(1.0));
  std::vector<bool> placed(a.skins.size(), false);
  for (size_t n = 0; n < a.nodes.size(); ++n) {
    const int s = a.nodes[n].skin;
    if (s < 0 || placed[size_t(s)]) continue;
    placement[size_t(s)] = rest.world[n];
    placed[size_t(s)] = true;
  }
  return placement;
}

void check_inverse_binds(const Asset& a, size_t s, const Pose& rest, const Mat4<double>& placement,
                         const LintOptions& o, Findings& out) {
  const Skin& skin = a.skins[s];
  const double size = skeleton_size(skin, rest);
  const Mat4<double> unplace = glm::inverse(placement);
  for (size_t j = 0; j < skin.joints.size(); ++j) {
    const Mat4<double>& ibm = skin.inverse_bind[j];
    const Mat4<double> m = unplace * rest.world[size_t(skin.joints[j])] * ibm;
    double deviation = 0;
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) deviation = std::max(deviation, std::abs(m[c][r] - (c == r ? 1.0 : 0.0)));
    for (int r = 0; r < 3; ++r) deviation = std::max(deviation, std::abs(m[3][r]) / size);
    if (deviation > o.bind_tolerance)
      out["inverse-bind-mismatch"].add(deviation, joint_example(skin_name(s), j, deviation), [&] {
        return "inverse bind matrix of joint " + std::to_string(j) + " (" + node_name(a, skin.joints[j]) + ", " +
               skin_name(s) + ") is not the inverse of its rest world matrix: world · inverseBind differs from the " +
               "skinned mesh node's placement by " + number(deviation) +
               " (largest entry, translation relative to the skeleton's size " + number(size) + ")";
      });
    const JointSplit<double> split = split_joint_matrix(ibm, o.scale_tolerance);
    if (!split.is_rigid) {
      const double d = measure(split.scale).off_identity;
      out["ibm-not-orthonormal"].add(d, joint_example(skin_name(s), j, d), [&] {
        return "inverse bind matrix of joint " + std::to_string(j) + " (" + node_name(a, skin.joints[j]) + ", " +
               skin_name(s) + ") has scale or shear (|S − I| up to " + number(d) + ")";
      });
    }
  }
}

// Worst case per joint over every pose, so that a joint is counted once however many keys show it.
struct JointWorst {
  double score = -1;
  LintExample example;
  std::string message;
};

void check_joint_scale(const Asset& rig, const LintOptions& o, Findings& out) {
  std::map<std::pair<size_t, size_t>, JointWorst> uniform, nonuniform;
  auto visit = [&](const Pose& pose, const std::string& when) {
    for (size_t s = 0; s < rig.skins.size(); ++s) {
      const Skin& skin = rig.skins[s];
      for (size_t j = 0; j < skin.joints.size(); ++j) {
        const Mat4<double> m = pose.world[size_t(skin.joints[j])] * skin.inverse_bind[j];
        const JointSplit<double> split = split_joint_matrix(m, o.scale_tolerance);
        if (split.is_rigid) continue;
        const ScaleMeasure d = measure(split.scale);
        const bool is_uniform = d.off_uniform <= o.scale_tolerance;
        JointWorst& w = (is_uniform ? uniform : nonuniform)[{s, j}];
        const double score = is_uniform ? d.off_identity : d.off_uniform;
        if (score <= w.score) continue;
        w.score = score;
        w.example = joint_example(skin_name(s) + " " + when, j, score);
        w.message =
            "joint matrix of joint " + std::to_string(j) + " (" + node_name(rig, skin.joints[j]) + ", " + skin_name(s) +
            ") " + when + " has " +
            (is_uniform
                 ? "uniform scale " + number((split.scale[0][0] + split.scale[1][1] + split.scale[2][2]) / 3) +
                       " (DQS with the two-phase rule keeps it)"
                 : "non-uniform scale or shear (|S − sI| up to " + number(score) + "; DQS needs the two-phase path)");
      }
    }
  };
  visit(sample_pose(rig, nullptr, 0), "at rest");
  for (size_t c = 0; c < rig.clips.size(); ++c) {
    const Clip& clip = rig.clips[c];
    std::set<float> key_times;
    for (const Channel& ch : clip.channels) key_times.insert(ch.times.begin(), ch.times.end());
    const std::vector<float> times(key_times.begin(), key_times.end());
    // Each pose costs about (nodes + channels + every skin's joints: one polar decomposition each) steps. A
    // clip with more key times than kPoseWork allows is sampled at evenly spaced ones, first and last
    // included, so that a hostile file cannot make lint run for hours (the shared models stay far below it:
    // BrainStem has 22 nodes and at most 1,309 keys a channel).
    constexpr size_t kPoseWork = 50'000'000;
    size_t per_pose = rig.nodes.size() + clip.channels.size() + 1;
    for (const Skin& skin : rig.skins) per_pose += skin.joints.size();
    const size_t poses = std::max<size_t>(2, kPoseWork / per_pose);
    const size_t step = times.size() > poses ? (times.size() + poses - 1) / poses : 1;
    for (size_t i = 0; i < times.size(); i += step) {
      const size_t k = i + step >= times.size() ? times.size() - 1 : i;
      const double t = double(times[k]);
      check_cancelled(o.cancel);
      visit(sample_pose(rig, &clip, t), "in animation '" + clip.name + "' at " + number(t) + " s");
      if (k == times.size() - 1) break;
    }
  }
  for (const auto& [check, joints] :
       {std::pair{"joint-uniform-scale", &uniform}, std::pair{"joint-nonuniform-scale", &nonuniform}})
    for (const auto& entry : *joints) {
      const JointWorst& w = entry.second;
      out[check].add(w.score, w.example, [&] { return w.message; });
    }
}

}  // namespace

void check_skeletons(const gltf::SkinData& data, const LintOptions& options, Findings& out) {
  // The rest pose and the clips, without meshes: sampling then needs no morph weights.
  Asset rig;
  rig.nodes = data.structure.nodes;
  for (Node& n : rig.nodes) n.mesh = -1;
  rig.skins = data.structure.skins;
  rig.clips = data.structure.clips;
  const Pose rest = sample_pose(rig, nullptr, 0);
  const NodeTree tree(rig.nodes);
  const std::vector<Mat4<double>> placements = bind_placements(rig, rest);
  for (size_t s = 0; s < rig.skins.size(); ++s) {
    check_cancelled(options.cancel);
    check_roots(rig, tree, s, out);
    check_inverse_binds(rig, s, rest, placements[s], options, out);
  }
  check_joint_scale(rig, options, out);
}

}  // namespace dqskin::lint
