// The checks of `dqskin lint` (internal to lib/lint), one function per group, each adding what it finds to
// a Findings keyed by check id. Each check counts its cases and keeps the worst one (the largest score).
#pragma once

#include "../gltf/skin_data.hpp"
#include "dqskin/lint.hpp"

#include <map>
#include <string>

namespace dqskin::lint {

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

// Common roots and the skeleton property, inverse bind matrices against the rest pose and their
// orthonormality, scale and shear of joint matrices at rest and at every key time (skeleton_checks.cpp).
void check_skeletons(const gltf::SkinData& data, const LintOptions& options, Findings& out);

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
