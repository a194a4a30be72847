// Crossfading two clips, the reference way (docs/DESIGN.md §3.10): what an engine's animation mixer does.
// Each clip is sampled into node-LOCAL transforms, the two local poses are blended per node, and only then
// are world matrices composed through the hierarchy. The crossfade models of the textures
// (skin/crossfade.hpp) are measured against the deformation of this blended pose.
#pragma once

#include "dqskin/animation.hpp"
#include "dqskin/asset.hpp"

#include <vector>

namespace dqskin {

// Every node's local transform and morph weights at one time: a Pose before the hierarchy.
struct LocalPose {
  std::vector<LocalTransform> local;         // per node
  std::vector<std::vector<double>> weights;  // per node: its mesh's morph weights (empty without targets)
};

// `clip` (null: the rest pose) at `time` seconds, channels applied to the nodes' rest transforms exactly
// as sample_pose does: world_pose(asset, sample_local_pose(asset, clip, t)) == sample_pose(asset, clip, t).
LocalPose sample_local_pose(const Asset& asset, const Clip* clip, double time);

// World matrices parent first, as sample_pose composes them.
Pose world_pose(const Asset& asset, const LocalPose& local);

// The crossfade of two local poses of the same asset at weight w (0: a, 1: b), per node: translation and
// scale lerped, rotation slerped along the shorter arc, morph weights lerped. A node given by a matrix
// (glTF forbids animating those) keeps a's matrix.
LocalPose blend_local_poses(const LocalPose& a, const LocalPose& b, double w);

// The reference's blended pose: world_pose(asset, blend_local_poses(a, b, w)).
Pose blend_poses(const Asset& asset, const LocalPose& a, const LocalPose& b, double w);

}  // namespace dqskin
