// The per-joint checks of `dqskin lint`: the joints' hierarchy (glTF 2.0 §3.7.3.1 and the skin schema:
// joints share a common root, and `skeleton` is that root or one of its ancestors), and the joint matrices
// world · inverseBind at rest and at every key: scaled to zero, mirrored, and scaled
// (docs/DESIGN.md §3.6: uniform scale survives DQS with the two-phase rule; shear and non-uniform scale
// need it, and plain DQS runtimes distort them). Scale is measured against the skin's placement
// (SkinFrame::scale), so an armature at 0.01 scale is not a scaled joint. Inverse bind matrices: bind_checks.cpp.
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

std::string node_name(const Asset& a, int node) {
  std::string s = "node " + std::to_string(node);
  if (!a.nodes[size_t(node)].name.empty()) s += " '" + a.nodes[size_t(node)].name + "'";
  return s;
}

namespace {

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

// The smallest scale of a 3×3 A, within a factor √3: |det A| / |adj A| (Frobenius), since A⁻¹ = adj A / det A
// and 1 / |A⁻¹|_F ≤ σ_min ≤ √3 / |A⁻¹|_F. 0 for a singular A. Cheap, and needs no eigenvalues.
double smallest_scale(const Mat3<double>& a) {
  // The rows of adj A are the columns' cross products.
  const Vec3<double> rows[3] = {glm::cross(a[1], a[2]), glm::cross(a[2], a[0]), glm::cross(a[0], a[1])};
  const double norm = glm::dot(rows[0], rows[0]) + glm::dot(rows[1], rows[1]) + glm::dot(rows[2], rows[2]);
  return norm > 0 ? std::abs(glm::determinant(a)) / std::sqrt(norm) : 0.0;
}

// Worst case per joint over every pose, so that a joint is counted once however many keys show it.
struct JointWorst {
  double score = -1;
  LintExample example;
  std::string message;
};

void check_joint_scale(const Asset& rig, const Pose& rest, const std::vector<SkinFrame>& frames, const LintOptions& o,
                       Findings& out) {
  std::map<std::pair<size_t, size_t>, JointWorst> zero, mirrored, uniform, nonuniform;
  auto keep = [](JointWorst& w, double score, auto make_example, auto make_message) {
    if (score <= w.score) return;
    w.score = score;
    w.example = make_example();
    w.message = make_message();
  };
  auto visit = [&](const Pose& pose, const std::string& when) {
    for (size_t s = 0; s < rig.skins.size(); ++s) {
      const Skin& skin = rig.skins[s];
      const SkinFrame& f = frames[s];
      for (size_t j = 0; j < skin.joints.size(); ++j) {
        if (!f.bind_usable[j]) continue;  // ibm-not-affine or ibm-not-invertible says why
        // Scale relative to the skin's placement: an armature at 0.01 scales every joint alike, which is
        // where the mesh is placed, not how it deforms.
        Mat4<double> m = pose.world[size_t(skin.joints[j])] * skin.inverse_bind[j];
        for (int c = 0; c < 3; ++c) m[c] /= f.scale;
        const Mat3<double> a(m);
        // Built only for a new worst case: a pose visits every joint of every skin.
        const auto joint = [&] {
          return "joint matrix of joint " + std::to_string(j) + " (" + node_name(rig, skin.joints[j]) + ", " +
                 skin_name(s) + ") " + when;
        };
        const auto example = [&](double value) { return joint_example(skin_name(s) + " " + when, j, value); };
        const double smallest = smallest_scale(a);
        if (!(smallest >= o.scale_tolerance)) {
          keep(zero[{s, j}], o.scale_tolerance - smallest, [&] { return example(smallest); }, [&] {
            return joint() + " scales to zero (smallest scale about " + number(smallest) + " of the skin's " +
                   number(f.scale) + "): its vertices collapse and their normals are undefined (three.js normalizes a "
                   "zero vector; DQS has no rotation to blend)";
          });
          continue;
        }
        const double det = glm::determinant(a);
        if (det < 0) {
          keep(mirrored[{s, j}], -det, [&] { return example(det); }, [&] {
            return joint() + " mirrors (determinant " + number(det) + "): its triangles turn inside out, and runtimes " +
                   "pick the front face from the mesh node's matrix, not the joint's (three.js), so single-sided " +
                   "materials show their back faces; DQS cannot represent a reflection";
          });
          continue;
        }
        const JointSplit<double> split = split_joint_matrix(m, o.scale_tolerance);
        if (split.is_rigid) continue;
        const ScaleMeasure d = measure(split.scale);
        const bool is_uniform = d.off_uniform <= o.scale_tolerance;
        const double score = is_uniform ? d.off_identity : d.off_uniform;
        keep((is_uniform ? uniform : nonuniform)[{s, j}], score, [&] { return example(score); }, [&] {
          return joint() + " has " +
                 (is_uniform ? "uniform scale " + number((split.scale[0][0] + split.scale[1][1] + split.scale[2][2]) / 3) +
                                   " of the skin's " + number(f.scale) + " (DQS with the two-phase rule keeps it)"
                             : "non-uniform scale or shear (|S − sI| up to " + number(score) + " of the skin's scale " +
                                   number(f.scale) +
                                   "): three.js turns normals by the blended joint matrix, not its inverse transpose, "
                                   "so lit shading is off there; DQS needs the two-phase path");
        });
      }
    }
  };
  visit(rest, "at rest");
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
       {std::pair{"joint-zero-scale", &zero}, std::pair{"joint-mirrored", &mirrored},
        std::pair{"joint-uniform-scale", &uniform}, std::pair{"joint-nonuniform-scale", &nonuniform}})
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
  rig.scenes = data.structure.scenes;
  const Pose rest = sample_pose(rig, nullptr, 0);
  const NodeTree tree(rig.nodes);
  for (size_t s = 0; s < rig.skins.size(); ++s) {
    check_cancelled(options.cancel);
    check_roots(rig, tree, s, out);
  }
  check_scenes(rig, tree, out);
  const std::vector<SkinFrame> frames = skin_frames(rig, rest);
  check_inverse_binds(rig, rest, frames, options, out);
  check_joint_scale(rig, rest, frames, options, out);
}

}  // namespace dqskin::lint
