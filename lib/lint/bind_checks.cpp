// The inverse bind matrix checks of `dqskin lint`. glTF 2.0 §3.7.3.1: the inverse bind matrices define the
// bind pose (the pose the mesh's POSITION was modelled in), the node transforms the rest pose; the two may
// differ (a character modelled in T-pose and exported with its arms down), and the armature may carry any
// transform (an FBX armature at 0.01 with joints in centimetres). Neither changes the deformation, so
// neither is a warning. What is:
// - a matrix whose fourth row is not (0, 0, 0, 1) (the skin schema requires it; the Khronos validator says
//   ACCESSOR_INVALID_IBM; three.js drops the w its shader computes, so runtimes disagree);
// - a matrix that cannot be inverted (no bind pose: Babylon inverts it to build its bones);
// - a bind pose that is no pose of the skeleton: a joint bound away from where its parent joint's bind
//   transform and its own unanimated offset put it. No clip can reach that pose, so the mesh tears or
//   stretches at the joint in every pose, in every runtime.
#include "lint_checks.hpp"

#include "dqskin/job.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace dqskin::lint {
namespace {

// The fourth row may differ from (0, 0, 0, 1) by float rounding, no more.
constexpr double kAffineTolerance = 1e-6;
// |det A| / (|a0| |a1| |a2|): 1 for orthogonal columns of any length, 0 for columns in one plane. Below
// this the matrix is singular as far as float data can tell (its columns are within about 1e-6 rad of
// one plane); the measure does not depend on scale, so a 0.01 armature's 100 × matrices pass.
constexpr double kSingularTolerance = 1e-6;

std::string skin_name(size_t s) { return "skin " + std::to_string(s); }

LintExample joint_example(size_t s, size_t joint, double value) {
  LintExample e;
  e.where = skin_name(s);
  e.joint = static_cast<long long>(joint);
  e.value = value;
  return e;
}

std::string joint_name(const Asset& a, size_t s, size_t j) {
  return "joint " + std::to_string(j) + " (" + node_name(a, a.skins[s].joints[j]) + ", " + skin_name(s) + ")";
}

double affine_error(const Mat4<double>& m) {
  return std::max({std::abs(m[0][3]), std::abs(m[1][3]), std::abs(m[2][3]), std::abs(m[3][3] - 1)});
}

// |det| of the 3×3 part over the product of its column lengths (0 when a column is 0).
double volume_ratio(const Mat4<double>& m) {
  const Mat3<double> a(m);
  const double lengths = glm::length(a[0]) * glm::length(a[1]) * glm::length(a[2]);
  return lengths > 0 ? std::abs(glm::determinant(a)) / lengths : 0.0;
}

bool is_finite(const Mat4<double>& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// Nodes whose transform a clip animates (any of translation, rotation, scale), and those whose translation.
struct Animated {
  std::vector<bool> any, translation;
};
Animated animated_nodes(const Asset& rig) {
  Animated a{std::vector<bool>(rig.nodes.size(), false), std::vector<bool>(rig.nodes.size(), false)};
  for (const Clip& clip : rig.clips)
    for (const Channel& ch : clip.channels) {
      if (ch.node < 0 || size_t(ch.node) >= rig.nodes.size() || ch.path == TargetPath::kWeights) continue;
      a.any[size_t(ch.node)] = true;
      if (ch.path == TargetPath::kTranslation) a.translation[size_t(ch.node)] = true;
    }
  return a;
}

// The nearest joint of a skin at or above a node, and whether a clip animates a node from there up to it
// (the joint excluded). One map per skin, filled as the walks pass: each node is walked over once per
// skin, so a chain of joints costs its length, not its length squared.
class JointAbove {
public:
  struct Up {
    int joint = -1;      // the skin's joint index, or -1 when none is above
    bool moves = false;  // an animated node below that joint, down to the node asked about
  };

  JointAbove(const Asset& rig, const Skin& skin, const Animated& animated) : rig_(rig), animated_(animated) {
    for (size_t j = 0; j < skin.joints.size(); ++j) index_.emplace(skin.joints[j], int(j));
  }

  Up at(int node) {
    Up found;
    path_.clear();
    for (int n = node; n >= 0; n = rig_.nodes[size_t(n)].parent) {
      if (const auto j = index_.find(n); j != index_.end()) {
        found = {j->second, false};
        break;
      }
      if (const auto m = memo_.find(n); m != memo_.end()) {
        found = m->second;
        break;
      }
      path_.push_back(n);
    }
    // Down from the highest node walked: each one adds its own animation to what is above it.
    for (auto n = path_.rbegin(); n != path_.rend(); ++n) {
      found.moves = found.moves || animated_.any[size_t(*n)];
      memo_[*n] = found;
    }
    return found;
  }

private:
  const Asset& rig_;
  const Animated& animated_;
  std::unordered_map<int, int> index_;  // node → joint index
  std::unordered_map<int, Up> memo_;
  std::vector<int> path_;
};

double uniform_scale(const Mat4<double>& m) { return std::cbrt(std::abs(glm::determinant(Mat3<double>(m)))); }

}  // namespace

std::vector<SkinFrame> skin_frames(const Asset& rig, const Pose& rest) {
  const Animated animated = animated_nodes(rig);
  std::vector<SkinFrame> frames(rig.skins.size());
  for (size_t s = 0; s < rig.skins.size(); ++s) {
    const Skin& skin = rig.skins[s];
    SkinFrame& f = frames[s];
    const size_t n = skin.joints.size();
    f.parent.assign(n, -1);
    f.offset_moves.assign(n, false);
    f.bind_usable.assign(n, false);
    JointAbove above(rig, skin, animated);
    Vec3<double> lo(0.0), hi(0.0);
    bool any = false;
    for (size_t j = 0; j < n; ++j) {
      const int node = skin.joints[j];
      const int parent_node = rig.nodes[size_t(node)].parent;
      const JointAbove::Up up = parent_node >= 0 ? above.at(parent_node) : JointAbove::Up{};
      f.parent[j] = up.joint;
      f.offset_moves[j] = up.moves || animated.translation[size_t(node)];
      const Mat4<double>& ibm = skin.inverse_bind[j];
      f.bind_usable[j] = is_finite(ibm) && affine_error(ibm) <= kAffineTolerance && volume_ratio(ibm) >= kSingularTolerance;
      if (!f.bind_usable[j]) continue;
      const Vec3<double> p(glm::inverse(ibm)[3]);
      lo = any ? glm::min(lo, p) : p;
      hi = any ? glm::max(hi, p) : p;
      any = true;
      if (f.reference < 0 && f.parent[j] < 0) f.reference = int(j);
    }
    const double diagonal = glm::length(hi - lo);
    f.size = diagonal > 0 && std::isfinite(diagonal) ? diagonal : 1.0;
    if (f.reference >= 0) {
      f.placement = rest.world[size_t(skin.joints[size_t(f.reference)])] * skin.inverse_bind[size_t(f.reference)];
      const double c = uniform_scale(f.placement);
      f.scale = c > 0 && std::isfinite(c) ? c : 1.0;
    }
  }
  return frames;
}

void check_inverse_binds(const Asset& rig, const Pose& rest, const std::vector<SkinFrame>& frames,
                         const LintOptions& o, Findings& out) {
  for (size_t s = 0; s < rig.skins.size(); ++s) {
    check_cancelled(o.cancel);
    const Skin& skin = rig.skins[s];
    const SkinFrame& f = frames[s];
    std::vector<bool> mismatched(skin.joints.size(), false);
    for (size_t j = 0; j < skin.joints.size(); ++j) {
      const Mat4<double>& ibm = skin.inverse_bind[j];
      if (!is_finite(ibm)) {
        out["ibm-not-invertible"].add(1, joint_example(s, j, 0), [&] {
          return "inverse bind matrix of " + joint_name(rig, s, j) + " has a value that is not a finite number";
        });
        continue;
      }
      const double affine = affine_error(ibm);
      if (affine > kAffineTolerance)
        out["ibm-not-affine"].add(affine, joint_example(s, j, affine), [&] {
          return "inverse bind matrix of " + joint_name(rig, s, j) + " has fourth row (" + number(ibm[0][3]) + ", " +
                 number(ibm[1][3]) + ", " + number(ibm[2][3]) + ", " + number(ibm[3][3]) +
                 "), not (0, 0, 0, 1): a projective matrix, which runtimes apply differently";
        });
      const double volume = volume_ratio(ibm);
      if (volume < kSingularTolerance)
        out["ibm-not-invertible"].add(1 - volume, joint_example(s, j, volume), [&] {
          return "inverse bind matrix of " + joint_name(rig, s, j) + " cannot be inverted (|det| / column lengths " +
                 number(volume) + "): it defines no bind pose";
        });
    }

    // The bind pose as a pose of the skeleton: joint j's bind position is where its parent's bind transform
    // B_p = inverseBind_p⁻¹ puts j's rest offset from p (the rest world matrices' W_p⁻¹ W_j), unless a clip
    // moves that offset (then the bind pose may be one the clip reaches).
    for (size_t j = 0; j < skin.joints.size(); ++j) {
      const int p = f.parent[j];
      if (p < 0 || f.offset_moves[j] || !f.bind_usable[j] || !f.bind_usable[size_t(p)]) continue;
      const Mat4<double>& parent_world = rest.world[size_t(skin.joints[size_t(p)])];
      if (volume_ratio(parent_world) < kSingularTolerance) continue;  // a parent scaled to zero at rest
      const Mat4<double> offset = glm::inverse(parent_world) * rest.world[size_t(skin.joints[j])];
      const Vec3<double> expected(glm::inverse(skin.inverse_bind[size_t(p)]) * offset[3]);
      const Vec3<double> bound(glm::inverse(skin.inverse_bind[j])[3]);
      const double distance = glm::distance(expected, bound);
      const double relative = distance / f.size;
      if (!(relative > o.bind_tolerance)) continue;
      mismatched[j] = true;
      out["inverse-bind-mismatch"].add(relative, joint_example(s, j, relative), [&] {
        return joint_name(rig, s, j) + " is bound " + number(distance) + " (" + number(relative) +
               " of the skeleton's " + number(f.size) + ") from where joint " + std::to_string(p) +
               "'s inverse bind matrix and its rest offset put it: the inverse bind matrices match no pose of the "
               "skeleton, so the mesh tears or stretches there in every pose";
      });
    }

    // Joints posed at rest unlike the bind pose, measured against the reference joint (so that the
    // armature's own transform, the same for every joint, does not count).
    if (f.reference < 0 || volume_ratio(f.placement) < kSingularTolerance) continue;
    const Mat4<double> unplace = glm::inverse(f.placement);
    for (size_t j = 0; j < skin.joints.size(); ++j) {
      if (!f.bind_usable[j] || mismatched[j]) continue;
      const Mat4<double> m = unplace * rest.world[size_t(skin.joints[j])] * skin.inverse_bind[j];
      double deviation = 0;
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) deviation = std::max(deviation, std::abs(m[c][r] - (c == r ? 1.0 : 0.0)));
      for (int r = 0; r < 3; ++r) deviation = std::max(deviation, std::abs(m[3][r]) / f.size);
      if (!(deviation > o.bind_tolerance)) continue;
      out["rest-differs-from-bind"].add(deviation, joint_example(s, j, deviation), [&] {
        return joint_name(rig, s, j) + " is posed at rest unlike its bind pose (world · inverseBind differs from "
               "joint " + std::to_string(f.reference) + "'s by " + number(deviation) +
               ": largest entry, translation relative to the skeleton's size " + number(f.size) +
               "); legal: viewers show the rest pose when no clip plays";
      });
    }
  }
}

}  // namespace dqskin::lint
