// Bone-texture profiles: one skin's joint transforms, frame by frame, written in the layout a runtime's
// shader reads (docs/DESIGN.md §4.1, §4.2), and read back as that shader reads it.
//
//   dq        the project's own BoneTexture (pack_bone_texture): DQS with the two-phase scale rule.
//   dq-cocos  Cocos Creator's baked dual-quaternion joint texture (skeletal-animation-utils.ts,
//             uploadJointDataDQS; shader chunk skinning-animation-dqs, skinRTS).
//   mat3x4    PlayCanvas's bone texture: the three rows of the affine 3×4 joint matrix; LBS.
//   mat4      Babylon.js's baked vertex-animation texture (the columns of each 4×4 joint matrix, the
//             order of three.js's boneMatrices too); LBS.
//
// The decoders here are the CPU's model of each shader, so that what a runtime will draw can be checked
// without that runtime: decode_joint_matrix for one joint, skin_vertex for one vertex.
#pragma once

#include "dqskin/skinning.hpp"

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace dqskin {

enum class BoneProfile { kDq, kDqCocos, kMat3x4, kMat4 };

// "dq", "dq-cocos", "mat3x4", "mat4". parse returns false (out untouched) for any other text.
bool parse_bone_profile(const std::string& text, BoneProfile& out);
const char* to_string(BoneProfile profile);

// The blend mode (to_string(BlendMode) spelling) that a profile's shader performs:
//   "dqs"  dq: DLB of the rigid parts with the antipodality pivot and the two-phase scale rule;
//          dq-cocos: Cocos's DLB variant (signs fixed per frame against joint 0 when packing, no pivot in
//          the shader, per-axis scale blended linearly).
//   "lbs"  mat3x4, mat4: the linear blend Σ w M of the joint matrices.
const char* implied_blend(BoneProfile profile);

// What is written, texel for texel: RGBA32F, row-major, row 0 first; texel (x, y) starts at
// rgba[4 (y width + x)]. Padding texels are zero.
struct BoneImage {
  BoneProfile profile = BoneProfile::kDq;
  size_t width = 0, height = 0;
  size_t joints = 0, frames = 0;
  int texels_per_joint = 0;
  std::vector<float> rgba;  // width × height × 4
};

// Packs one skin's JointTransforms, one per frame (all with the same joint count), in `profile`'s layout.
// No frames or no joints give an empty image (width = height = 0).
BoneImage pack_bones(BoneProfile profile, std::span<const JointTransforms> frames);

// The width and height pack_bones gives `joints` joints over `frames` frames (dq: with
// `dq_texels_per_joint`, 2 for rigid joints or 5; the other profiles' are fixed).
struct BoneImageSize {
  size_t width = 0, height = 0;
};
BoneImageSize bone_image_size(BoneProfile profile, size_t joints, size_t frames, int dq_texels_per_joint = 2);

// Why an image of `size` in `profile`'s layout cannot be written within `max_size` texels a side (0: no
// bound), as the end of a one-line error: what it needs and the --max-size that would fit it; empty when it
// fits. No profile wraps: each runtime addresses a joint by (texel, frame) in one image (dq: skin.comp;
// mat3x4: a row per frame; Babylon.js: row = frame, column = 4 · joint + k; Cocos: a square whose side it
// derives from the texel count), so a larger image or fewer frames is the only way.
std::string bone_size_problem(BoneProfile profile, BoneImageSize size, size_t max_size);

// The joint's transform at `frame`, read from the texels as the profile's shader reads them, as an
// affine matrix (for the DQ profiles the matrix the normalized dual quaternion and scale stand for).
// joint < image.joints and frame < image.frames.
Mat4<double> decode_joint_matrix(const BoneImage& image, size_t joint, size_t frame);

struct SkinnedVertex {
  Vec3<double> position, normal;
};

// Skins one vertex at `frame` from the texels as the profile's shader does, in double precision:
// up to kMaxInfluences influences (joints and weights of one size; weights ≤ 0 are skipped). The normal is returned
// unit (every runtime normalizes before shading; zero stays zero) and transformed as the runtime does:
//   dq        weights divided by their sum (as skin.comp), DLB via blend_dlb, S blended linearly;
//             p' = rigid(S p), n' = R cofactor(S) n. No weight at all leaves the vertex as it is.
//   dq-cocos  weights used as given (Cocos does not renormalize); n' = R n: Cocos does not correct the
//             normal for scale, so non-uniform scale tilts normals there and here alike.
//   mat3x4, mat4  M = Σ w M_j with weights as given; p' = M p, n' = mat3(M) n (PlayCanvas, Babylon and
//             three.js transform skinned normals by the blended 3×3 itself, not its inverse transpose).
SkinnedVertex skin_vertex(const BoneImage& image, size_t frame, std::span<const int> joints,
                          std::span<const float> weights, const Vec3<double>& position, const Vec3<double>& normal);

// One-line descriptions for side files: where each value sits (texel_formula) and what the reading shader
// computes from it (decode_formula).
std::string texel_formula(BoneProfile profile);
std::string decode_formula(BoneProfile profile);

}  // namespace dqskin
