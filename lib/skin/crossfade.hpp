// The runtime models of a crossfade between two baked frames (docs/DESIGN.md §3.10): clip A at frame i
// and clip B at frame j, weight w (0: A, 1: B). A vertex-animation texture can only lerp the two deformed
// frames; a dual-quaternion bone texture blends each joint's two skinning transforms before skinning.
// Both are measured against the deformation of the blended pose (anim/pose_blend.hpp).
#pragma once

#include "dqskin/skinning.hpp"

#include <vector>

namespace dqskin {

// The VAT crossfade, what a VAT shader does with two rows: positions (1 − w)·a + w·b; normals and
// tangents' directions lerped and renormalized (a's where the lerp vanishes; tangents keep a's w). The two
// frames must have the same primitives and vertex counts.
DeformedPrimitive vat_crossfade(const DeformedPrimitive& a, const DeformedPrimitive& b, double w);
DeformedFrame vat_crossfade(const DeformedFrame& a, const DeformedFrame& b, double w);

// The DQ crossfade of one skin's joint transforms, per joint: the rigid parts by DLB of two
// (normalize((1 − w)·qa + w·qb) with the deformer's antipodality rule, docs/DESIGN.md §3.5), the scale
// parts S lerped (the two-phase rule, §3.6). matrices become [R | t]·S of the result. Same joint count.
JointTransforms dq_crossfade(const JointTransforms& a, const JointTransforms& b, double w);

// Every primitive of every instance skinned with the DQ crossfade of pose a's and pose b's joint
// transforms, in `mode` (the `dq` profile's runtime is dqs). Morph weights are lerped (the bone texture
// does not carry them; a runtime lerps them as it would any other per-frame value). A rigid instance
// blends its node's world matrix the same way, as a one-joint skin.
DeformedFrame dq_crossfade_frame(const Asset& asset, const std::vector<MeshInstance>& instances, const Pose& a,
                                 const Pose& b, double w, BlendMode mode);

}  // namespace dqskin
