// Bone-texture profiles (bone_profiles.hpp): the layouts runtimes read, and CPU models of their shaders.
//
// Sources of each layout, read to learn the format (nothing is copied):
//   dq-cocos  cocos-engine cocos/3d/skeletal-animation/skeletal-animation-utils.ts (uploadJointDataDQS,
//             roundUpTextureSize, JointTexturePool), editor/assets/chunks/.../skinning-animation-dqs.chunk
//             (getJointDQ, skinRTS, CCSkin) and cc-skinning.chunk (CCGetJointTextureCoords).
//   mat3x4    PlayCanvas's bone texture: three texels per bone, the rows of the 3×4 matrix.
//   mat4      Babylon.js's VertexAnimationBaker: each frame's Skeleton.getTransformMatrices() as one row
//             (bones + 1 matrices, the last the identity), four texels per matrix; its shader
//             (readMatrixFromRawSamplerVAT) reads frame f at texel row f, and Babylon's EXR decoder
//             (exrLoader.decoder.js ScanData, as three.js's EXRLoader) puts the file's first scanline in
//             the last texel row, so frame f is stored in the image's row height - 1 - f.
// Dual quaternions as docs/DESIGN.md §3.1: (x, y, z, w) with w scalar, dual = 0.5 (t, 0) real [Kavan eq. 1].
#include "bone_profiles.hpp"

#include "dqskin/bone_texture.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace dqskin {
namespace {

using DVec4 = glm::vec<4, double, glm::defaultp>;

constexpr BoneProfile kProfiles[] = {BoneProfile::kDq, BoneProfile::kDqCocos, BoneProfile::kMat3x4,
                                     BoneProfile::kMat4};

float* texel_at(BoneImage& image, size_t x, size_t y) {
  assert(x < image.width && y < image.height);
  return &image.rgba[4 * (y * image.width + x)];
}

const float* texel_at(const BoneImage& image, size_t x, size_t y) {
  assert(x < image.width && y < image.height);
  return &image.rgba[4 * (y * image.width + x)];
}

Quat<double> quat_of(const float* texel) {
  Quat<double> q;
  for (int c = 0; c < 4; ++c) q[c] = double(texel[c]);  // storage order x, y, z, w, as the texel
  return q;
}

Vec3<double> vec3_of(const float* texel) { return {double(texel[0]), double(texel[1]), double(texel[2])}; }

// The shaders' division of both parts by |real| (skin.comp, Cocos skinRTS): then real is unit, and the
// library's rotation and translation are the shaders' formulas (t = 2 dual real*).
DualQuat<double> shader_normalize(const Quat<double>& real, const Quat<double>& dual) {
  const double inv = 1.0 / glm::length(real);
  return DualQuat<double>(real * inv, dual * inv);
}

// det(S) S⁻ᵀ by columns: the normal transform of the two-phase rule, defined for singular S too.
Mat3<double> cofactor(const Mat3<double>& a) {
  return Mat3<double>(glm::cross(a[1], a[2]), glm::cross(a[2], a[0]), glm::cross(a[0], a[1]));
}

Vec3<double> unit_or_zero(const Vec3<double>& v) {
  const double length = glm::length(v);
  return length > 0 ? v / length : v;
}

// ---------------------------------------------------------------------------------------------------
// Cocos addressing: joints are a linear run of texels in a square texture whose side is a multiple of 12
// (roundUpTextureSize with no minimum; the side must divide by 12 so that 3- and 12-texel joints never
// straddle a row). The shader finds row and column from the side alone, so the texture is square.

size_t cocos_side(size_t texels) {
  size_t side = size_t(std::ceil(std::sqrt(double(texels)) / 12.0)) * 12;
  while (side * side < texels) side += 12;  // sqrt rounding for huge counts
  while (side > 12 && (side - 12) * (side - 12) >= texels) side -= 12;
  return std::max<size_t>(side, 12);
}

// Texel k of a joint at a frame: i = 3 (frame · joints + joint) + k at (i mod side, i div side), as
// CCGetJointTextureCoords computes it.
float* cocos_texel(BoneImage& image, size_t joint, size_t frame, size_t k) {
  const size_t index = 3 * (frame * image.joints + joint) + k;
  return texel_at(image, index % image.width, index / image.width);
}

const float* cocos_texel(const BoneImage& image, size_t joint, size_t frame, size_t k) {
  const size_t index = 3 * (frame * image.joints + joint) + k;
  return texel_at(image, index % image.width, index / image.width);
}

// Cocos's uploader stores +0 for −0 (makeStable: GLSL ES 1.0 highp decoding cannot tell them apart).
float cocos_stable(double x) {
  const float f = float(x);
  return f == 0.0f ? 0.0f : f;
}

void pack_cocos(BoneImage& image, std::span<const JointTransforms> frames) {
  const size_t side = cocos_side(3 * image.joints * image.frames);
  image.width = image.height = side;
  image.rgba.assign(side * side * 4, 0.0f);
  for (size_t f = 0; f < image.frames; ++f) {
    const JointTransforms& jt = frames[f];
    const Quat<double> first = jt.rigid[0].real;
    for (size_t j = 0; j < image.joints; ++j) {
      // Cocos's sign consistency: every joint of a frame in joint 0's hemisphere, both parts together,
      // because its shader sums the influences without a pivot.
      DualQuat<double> q = jt.rigid[j];
      if (j > 0 && glm::dot(first, q.real) < 0) q = -q;
      // Cocos splits A into R·diag(s) (Mat4.toRTS: column lengths, R from the normalized columns).
      // R here is the polar rotation of JointTransforms, the same R whenever A has no shear; s is
      // then each column's length, signed as S's diagonal so that a mirror survives. Shear is lost:
      // a sheared joint decodes to R·diag(s), not A.
      const Mat3<double> a(jt.matrices[j]);
      Vec3<double> scale;
      for (int i = 0; i < 3; ++i) scale[i] = std::copysign(glm::length(a[i]), jt.scale[j][i][i]);

      float* out[3];
      for (size_t k = 0; k < 3; ++k) out[k] = cocos_texel(image, j, f, k);
      for (int c = 0; c < 4; ++c) {
        out[0][c] = cocos_stable(q.real[c]);
        out[1][c] = cocos_stable(q.dual[c]);
      }
      for (int c = 0; c < 3; ++c) out[2][c] = cocos_stable(scale[c]);
    }
  }
}

// ---------------------------------------------------------------------------------------------------
// Matrix layouts: one row per frame.

void pack_mat3x4(BoneImage& image, std::span<const JointTransforms> frames) {
  image.width = 3 * image.joints;
  image.height = image.frames;
  image.rgba.assign(image.width * image.height * 4, 0.0f);
  for (size_t f = 0; f < image.frames; ++f) {
    for (size_t j = 0; j < image.joints; ++j) {
      const Mat4<double>& m = frames[f].matrices[j];
      for (size_t k = 0; k < 3; ++k) {
        float* texel = texel_at(image, 3 * j + k, f);
        for (int c = 0; c < 4; ++c) texel[c] = float(m[c][int(k)]);  // row k: A[k][0..2], t[k]
      }
    }
  }
}

// The image row of frame f in the mat4 layout: bottom-up, the first frame in the last row (above).
size_t mat4_row(const BoneImage& image, size_t frame) { return image.frames - 1 - frame; }

void pack_mat4(BoneImage& image, std::span<const JointTransforms> frames) {
  image.width = 4 * (image.joints + 1);
  image.height = image.frames;
  image.rgba.assign(image.width * image.height * 4, 0.0f);
  for (size_t f = 0; f < image.frames; ++f) {
    for (size_t j = 0; j <= image.joints; ++j) {
      // Babylon's baker writes the skeleton's bones + 1 matrices; the extra one is the identity.
      const Mat4<double> m = j < image.joints ? frames[f].matrices[j] : Mat4<double>(1.0);
      for (size_t k = 0; k < 4; ++k) {
        float* texel = texel_at(image, 4 * j + k, mat4_row(image, f));
        for (int c = 0; c < 4; ++c) texel[c] = float(m[int(k)][c]);  // column k
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------------
// Reading one joint back.

// A DQ profile's joint: real and dual as stored, and the scale matrix applied before the rigid part.
struct DqTexels {
  Quat<double> real, dual;
  Mat3<double> scale{1.0};
};

DqTexels read_dq(const BoneImage& image, size_t joint, size_t frame) {
  DqTexels out;
  if (image.profile == BoneProfile::kDqCocos) {
    out.real = quat_of(cocos_texel(image, joint, frame, 0));
    out.dual = quat_of(cocos_texel(image, joint, frame, 1));
    const Vec3<double> s = vec3_of(cocos_texel(image, joint, frame, 2));
    out.scale = Mat3<double>(s.x, 0.0, 0.0, 0.0, s.y, 0.0, 0.0, 0.0, s.z);  // p * S in the shader: per axis
    return out;
  }
  const size_t t = size_t(image.texels_per_joint), x = t * joint;
  out.real = quat_of(texel_at(image, x, frame));
  out.dual = quat_of(texel_at(image, x + 1, frame));
  if (t == 5)  // rows of the symmetric S, so also its columns (skin.comp bone_scale)
    out.scale = Mat3<double>(vec3_of(texel_at(image, x + 2, frame)), vec3_of(texel_at(image, x + 3, frame)),
                             vec3_of(texel_at(image, x + 4, frame)));
  return out;
}

Mat4<double> read_matrix(const BoneImage& image, size_t joint, size_t frame) {
  Mat4<double> m(1.0);
  if (image.profile == BoneProfile::kMat3x4) {
    for (int k = 0; k < 3; ++k) {
      const float* row = texel_at(image, 3 * joint + size_t(k), frame);
      for (int c = 0; c < 4; ++c) m[c][k] = double(row[c]);
    }
  } else {
    for (int k = 0; k < 4; ++k) {
      const float* column = texel_at(image, 4 * joint + size_t(k), mat4_row(image, frame));
      m[k] = DVec4(column[0], column[1], column[2], column[3]);
    }
  }
  return m;
}

// The affine matrix of p ↦ rotate(real, S p) + t after the shader's normalization by |real|.
Mat4<double> dq_matrix(const DqTexels& t) {
  const DualQuat<double> q = shader_normalize(t.real, t.dual);
  Mat4<double> m(1.0);
  for (int i = 0; i < 3; ++i) m[i] = DVec4(rotate_vector(q, t.scale[i]), 0.0);
  m[3] = DVec4(translation(q), 1.0);
  return m;
}

// ---------------------------------------------------------------------------------------------------
// Skinning one vertex.

struct Influences {
  size_t count = 0;
  size_t joint[kMaxInfluences];  // every influence the Asset holds (asset.hpp)
  double weight[kMaxInfluences];
};

Influences gather([[maybe_unused]] const BoneImage& image, std::span<const int> joints, std::span<const float> weights) {
  assert(joints.size() == weights.size() && joints.size() <= size_t(kMaxInfluences));
  Influences in;
  for (size_t k = 0; k < joints.size(); ++k) {
    if (!(weights[k] > 0)) continue;
    assert(joints[k] >= 0 && size_t(joints[k]) < image.joints);
    in.joint[in.count] = size_t(joints[k]);
    in.weight[in.count] = double(weights[k]);
    ++in.count;
  }
  return in;
}

// The project's DQS (docs/DESIGN.md §3.6): DLB of the rigid parts, S blended linearly and applied first.
SkinnedVertex skin_dq(const BoneImage& image, size_t frame, const Influences& in, const Vec3<double>& p,
                      const Vec3<double>& n) {
  double sum = 0;
  for (size_t k = 0; k < in.count; ++k) sum += in.weight[k];
  DualQuat<double> q[kMaxInfluences];
  double w[kMaxInfluences];
  Mat3<double> scale(0.0);
  for (size_t k = 0; k < in.count; ++k) {
    const DqTexels t = read_dq(image, in.joint[k], frame);
    q[k] = DualQuat<double>(t.real, t.dual);
    w[k] = in.weight[k] / sum;
    scale += t.scale * w[k];
  }
  const DualQuat<double> b = blend_dlb(std::span<const DualQuat<double>>(q, in.count), std::span<const double>(w, in.count));
  return {transform_point(b, scale * p), unit_or_zero(rotate_vector(b, cofactor(scale) * n))};
}

// Cocos's skinRTS and CCSkin: plain weighted sums (the packer fixed the signs), normal by R alone.
SkinnedVertex skin_cocos(const BoneImage& image, size_t frame, const Influences& in, const Vec3<double>& p,
                         const Vec3<double>& n) {
  Quat<double> real(0, 0, 0, 0), dual(0, 0, 0, 0);
  Vec3<double> scale(0.0);
  for (size_t k = 0; k < in.count; ++k) {
    const double w = in.weight[k];
    real = real + quat_of(cocos_texel(image, in.joint[k], frame, 0)) * w;
    dual = dual + quat_of(cocos_texel(image, in.joint[k], frame, 1)) * w;
    scale += vec3_of(cocos_texel(image, in.joint[k], frame, 2)) * w;
  }
  const DualQuat<double> q = shader_normalize(real, dual);
  return {transform_point(q, p * scale), unit_or_zero(rotate_vector(q, n))};
}

SkinnedVertex skin_matrices(const BoneImage& image, size_t frame, const Influences& in, const Vec3<double>& p,
                            const Vec3<double>& n) {
  Mat4<double> m[kMaxInfluences];
  for (size_t k = 0; k < in.count; ++k) m[k] = read_matrix(image, in.joint[k], frame);
  const Mat4<double> blended =
      blend_lbs(std::span<const Mat4<double>>(m, in.count), std::span<const double>(in.weight, in.count));
  return {Vec3<double>(blended * DVec4(p, 1.0)), unit_or_zero(Mat3<double>(blended) * n)};
}

}  // namespace

bool parse_bone_profile(const std::string& text, BoneProfile& out) {
  for (BoneProfile p : kProfiles) {
    if (text == to_string(p)) {
      out = p;
      return true;
    }
  }
  return false;
}

const char* to_string(BoneProfile profile) {
  switch (profile) {
    case BoneProfile::kDq: return "dq";
    case BoneProfile::kDqCocos: return "dq-cocos";
    case BoneProfile::kMat3x4: return "mat3x4";
    case BoneProfile::kMat4: return "mat4";
  }
  return "?";
}

const char* implied_blend(BoneProfile profile) {
  switch (profile) {
    case BoneProfile::kDq:
    case BoneProfile::kDqCocos: return to_string(BlendMode::kDqs);
    case BoneProfile::kMat3x4:
    case BoneProfile::kMat4: return to_string(BlendMode::kLbs);
  }
  return "?";
}

BoneImageSize bone_image_size(BoneProfile profile, size_t joints, size_t frames, int dq_texels_per_joint) {
  if (joints == 0 || frames == 0) return {};
  switch (profile) {
    case BoneProfile::kDq: return {size_t(dq_texels_per_joint) * joints, frames};
    case BoneProfile::kDqCocos: {
      const size_t side = cocos_side(3 * joints * frames);
      return {side, side};
    }
    case BoneProfile::kMat3x4: return {3 * joints, frames};
    case BoneProfile::kMat4: return {4 * (joints + 1), frames};
  }
  return {};
}

std::string bone_size_problem(BoneProfile profile, BoneImageSize size, size_t max_size) {
  if (max_size == 0 || (size.width <= max_size && size.height <= max_size)) return {};
  const size_t needed = std::max(size.width, size.height);
  std::string out = "the " + std::string(to_string(profile)) + " bone texture needs " + std::to_string(size.width) +
                    " × " + std::to_string(size.height) + " texels, over --max-size " + std::to_string(max_size);
  out += profile == BoneProfile::kDqCocos ? " (Cocos reads one square texture)"
                                          : " (its runtime reads one row per frame and does not wrap)";
  out += "; --max-size " + std::to_string(needed) + " would fit";
  if (profile != BoneProfile::kDqCocos && size.height > max_size) out += ", as would fewer frames (--fps)";
  return out;
}

BoneImage pack_bones(BoneProfile profile, std::span<const JointTransforms> frames) {
  BoneImage image;
  image.profile = profile;
  image.frames = frames.size();
  image.joints = frames.empty() ? 0 : frames.front().matrices.size();
  for ([[maybe_unused]] const JointTransforms& f : frames)
    assert(f.matrices.size() == image.joints && f.rigid.size() == image.joints && f.scale.size() == image.joints);
  if (image.joints == 0) image.frames = 0;
  switch (profile) {
    case BoneProfile::kDq: {
      image.texels_per_joint = 2;
      if (image.frames == 0) break;
      BoneTexture tex = pack_bone_texture(frames);
      image.texels_per_joint = tex.texels_per_joint;
      image.width = tex.width();
      image.height = tex.frames;
      image.rgba = std::move(tex.rgba);
      break;
    }
    case BoneProfile::kDqCocos:
      image.texels_per_joint = 3;
      if (image.frames > 0) pack_cocos(image, frames);
      break;
    case BoneProfile::kMat3x4:
      image.texels_per_joint = 3;
      if (image.frames > 0) pack_mat3x4(image, frames);
      break;
    case BoneProfile::kMat4:
      image.texels_per_joint = 4;
      if (image.frames > 0) pack_mat4(image, frames);
      break;
  }
  return image;
}

Mat4<double> decode_joint_matrix(const BoneImage& image, size_t joint, size_t frame) {
  assert(joint < image.joints && frame < image.frames);
  if (image.profile == BoneProfile::kMat3x4 || image.profile == BoneProfile::kMat4)
    return read_matrix(image, joint, frame);
  return dq_matrix(read_dq(image, joint, frame));
}

SkinnedVertex skin_vertex(const BoneImage& image, size_t frame, std::span<const int> joints,
                          std::span<const float> weights, const Vec3<double>& position, const Vec3<double>& normal) {
  assert(frame < image.frames);
  const Influences in = gather(image, joints, weights);
  if (in.count == 0) return {position, unit_or_zero(normal)};
  switch (image.profile) {
    case BoneProfile::kDq: return skin_dq(image, frame, in, position, normal);
    case BoneProfile::kDqCocos: return skin_cocos(image, frame, in, position, normal);
    case BoneProfile::kMat3x4:
    case BoneProfile::kMat4: return skin_matrices(image, frame, in, position, normal);
  }
  return {position, unit_or_zero(normal)};
}

std::string texel_formula(BoneProfile profile) {
  switch (profile) {
    case BoneProfile::kDq:
      return "T = 2 texels per joint (5 when any joint of any frame is non-rigid); texel (T*j + k, f): "
             "k = 0 real quaternion (x, y, z, w), k = 1 dual = 0.5 * (t, 0) * real, k = 2..4 the rows of "
             "the symmetric S of A = R S (xyz, w = 0)";
    case BoneProfile::kDqCocos:
      return "3 texels per joint in a linear run: i = 3 * (f * joints + j) + k at (i mod L, i div L), "
             "L = width = height = max(12, ceil(sqrt(3 * joints * frames) / 12) * 12); k = 0 real quaternion "
             "(x, y, z, w), k = 1 dual = 0.5 * (t, 0) * real, k = 2 per-axis scale (xyz, w = 0); both parts "
             "negated when dot(real_j, real_0) < 0 in the same frame";
    case BoneProfile::kMat3x4:
      return "3 texels per joint; texel (3*j + k, f) = row k of the affine joint matrix: "
             "(A[k][0], A[k][1], A[k][2], t[k])";
    case BoneProfile::kMat4:
      return "4 texels per joint; texel (4*j + k, frames - 1 - f) = column k of the 4x4 joint matrix (column 3 = "
             "(t, 1)); width = 4 * (joints + 1): the last 4 texels of each row are the identity; the first frame "
             "is the image's last row, texel row 0 once an OpenGL-convention EXR reader (Babylon.js's, "
             "three.js's) has read it bottom-up";
  }
  return "";
}

std::string decode_formula(BoneProfile profile) {
  switch (profile) {
    case BoneProfile::kDq:
      return "w_i /= sum(w); each influence negated when dot(real_i, real_pivot) < 0 (pivot: largest weight); "
             "real = sum(w_i real_i), dual = sum(w_i dual_i); real, dual /= length(real); "
             "t = 2 * (real.w * dual.xyz - dual.w * real.xyz + cross(real.xyz, dual.xyz)); S = sum(w_i S_i); "
             "p' = rotate(real, S p) + t; n' = rotate(real, cofactor(S) n)";
    case BoneProfile::kDqCocos:
      return "R = sum(w_i real_i), Qt = sum(w_i dual_i), S = sum(w_i scale_i); R, Qt *= 1 / length(R); "
             "T = 2 * (R.w * Qt.xyz - Qt.w * R.xyz + cross(R.xyz, Qt.xyz)); p' = rotate(p * S, R) + T; "
             "n' = rotate(n, R)";
    case BoneProfile::kMat3x4:
      return "row_k = sum(w_i row_k,i); p'.k = dot(row_k, (p, 1)); n'.k = dot(row_k.xyz, n)";
    case BoneProfile::kMat4:
      return "M = sum(w_i M_i); p' = (M * (p, 1)).xyz; n' = mat3(M) * n";
  }
  return "";
}

}  // namespace dqskin
