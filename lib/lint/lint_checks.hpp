// The checks of `dqskin lint` (internal to lib/lint), one function per group, each adding what it finds to
// a Findings keyed by check id. Each check counts its cases and keeps the worst one (the largest score).
#pragma once

#include "../load/skin_data.hpp"
#include "dqskin/animation.hpp"
#include "dqskin/lint.hpp"

#include <map>
#include <string>
#include <vector>

namespace dqskin::lint {

class NodeTree;

// One check's running count and worst example.
struct Tally {
  size_t count = 0;
  double score = 0;  // how bad the worst case is; larger is worse
  LintExample worst;
  std::string message;

  // Counts a case; it becomes the worst when its score is larger than every earlier one (the first of
  // equal ones stays, so results do not depend on anything but the file's order). `message` is built only
  // then.
  template <typename MakeMessage>
  void add(double case_score, const LintExample& example, MakeMessage make_message) {
    if (count++ == 0 || case_score > score) {
      score = case_score;
      worst = example;
      message = make_message();
    }
  }
};

using Findings = std::map<std::string, Tally>;  // by check id

// Weight sums, zero-weight vertices, negative weights, duplicate joints, joint indices out of range,
// influence counts, joints that influence nothing (influence_checks.cpp).
void check_influences(const gltf::SkinData& data, const LintOptions& options, Findings& out);

// Common roots and the skeleton property, joints outside the scene that draws their skin, skinned mesh
// nodes whose transform glTF ignores, inverse bind matrices, and the scale, shear and mirroring of joint
// matrices at rest and at every key time (skeleton_checks.cpp, with the parts below).
void check_skeletons(const gltf::SkinData& data, const LintOptions& options, Findings& out);

// What the checks of one skin measure against (bind_checks.cpp).
struct SkinFrame {
  std::vector<int> parent;         // per joint: the skin's joint nearest above it, or -1 (a top joint)
  std::vector<bool> offset_moves;  // per joint: a clip animates its translation or a node between it and parent
  std::vector<bool> bind_usable;   // per joint: its inverse bind matrix is finite, affine and invertible
  // Bounding-box diagonal of the joints' bind positions, in bind space (the units of POSITION); 1 when
  // every joint is bound at one point. Tolerances in scene units are this times the relative tolerance.
  double size = 1;
  int reference = -1;            // the first top joint with a usable inverse bind matrix, or -1
  Mat4<double> placement{1.0};   // its joint matrix world · inverseBind at rest: bind space placed in the world
  double scale = 1;              // placement's uniform scale, ∛|det|, or 1 when it has none (a 0.01 armature: 0.01)
};

// One SkinFrame per skin of `rig`, from the rest pose `rest`.
std::vector<SkinFrame> skin_frames(const Asset& rig, const Pose& rest);

// Inverse bind matrices that are not affine or not invertible, that match no pose of the skeleton, and
// joints posed at rest unlike their bind pose (bind_checks.cpp).
void check_inverse_binds(const Asset& rig, const Pose& rest, const std::vector<SkinFrame>& frames,
                         const LintOptions& options, Findings& out);

// Joints outside the scene that draws their skin, and skinned mesh nodes with a transform (scene_checks.cpp).
void check_scenes(const Asset& rig, const NodeTree& tree, Findings& out);

// "node 3 'Hips'"
std::string node_name(const Asset& asset, int node);

// Rotation keys that are not unit quaternions, and neighbours in opposite hemispheres (key_checks.cpp).
void check_rotation_keys(const gltf::SkinData& data, const LintOptions& options, Findings& out);

// Channels of one animation that repeat a target: with different keys (an error: the file cannot be
// deformed), and with the same keys (key_checks.cpp).
void check_channels(const gltf::SkinData& data, const LintOptions& options, Findings& out);

// "mesh 0 primitive 1"
std::string primitive_name(const gltf::SkinnedPrimitive& p);

// The largest stored value of a normalized integer component type (glTF 2.0 §3.11: the value is c / it,
// so it is also the unit of rounding), 0 for float.
double normalized_max(int component);

// The joint counts of the skins that deform the primitive (0 and 0, skins -1, when none does). An index
// below `fewest` fits every skin; one from `fewest` to below `most` fits the larger skins only: a mesh
// drawn by two skins may hold indices its larger skin needs, which only the node with the smaller skin
// draws wrong; an index of `most` or more fits none.
struct JointRange {
  size_t fewest = 0, most = 0;
  int smallest = -1, largest = -1;  // a skin with `fewest` joints and one with `most` (the first of equals)
};
JointRange joint_range(const gltf::SkinnedPrimitive& p, const Asset& asset);

// A number for messages: 6 significant digits (%g).
std::string number(double value);

}  // namespace dqskin::lint
