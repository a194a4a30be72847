// The "pack" stage of docs/DESIGN.md §1.1: every frame's JointTransforms of one skin packed into the
// BoneTexture that the compute shader reads and `dqskin bake --format bones` writes.
#pragma once

#include "dqskin/skinning.hpp"

#include <cstddef>
#include <span>
#include <vector>

namespace dqskin {

// The BoneTexture of docs/DESIGN.md §4.1: RGBA32F, one row per frame, T texels per joint (T = 2: real, dual;
// T = 5 when any joint of any frame is non-rigid: real, dual, then the three rows of S with w = 0).
// Texel (T·j + k, f) is component k of joint j at frame f, joints in the skin's order.
struct BoneTexture {
  int texels_per_joint = 2;
  size_t joints = 0;
  size_t frames = 0;
  std::vector<float> rgba;  // frames × joints × T × 4, row-major

  size_t width() const { return joints * size_t(texels_per_joint); }
};

// Packs one skin's JointTransforms, one per frame.
BoneTexture pack_bone_texture(std::span<const JointTransforms> frames);

// "palette" then "pack" for a batch of poses: the BoneTexture of every mesh instance, one row per pose.
// Instances drawn with one skin share its texture (packed once, copied).
std::vector<BoneTexture> pack_instance_textures(const Asset& asset, std::span<const MeshInstance> instances,
                                                std::span<const Pose> poses);

}  // namespace dqskin
