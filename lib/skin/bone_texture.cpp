// Packing JointTransforms into the BoneTexture layout of shared/DESIGN.md.
#include "dqskin/bone_texture.hpp"

namespace dqskin {

BoneTexture pack_bone_texture(std::span<const JointTransforms> frames) {
  BoneTexture tex;
  tex.frames = frames.size();
  tex.joints = frames.empty() ? 0 : frames.front().rigid.size();
  for (const JointTransforms& f : frames) tex.texels_per_joint = f.any_non_rigid ? 5 : tex.texels_per_joint;
  const size_t t = size_t(tex.texels_per_joint);
  tex.rgba.assign(tex.frames * tex.joints * t * 4, 0.0f);
  for (size_t f = 0; f < tex.frames; ++f) {
    for (size_t j = 0; j < tex.joints; ++j) {
      float* texel = &tex.rgba[((f * tex.joints + j) * t) * 4];
      const DualQuat<double>& q = frames[f].rigid[j];
      for (int c = 0; c < 4; ++c) {  // GLM order x, y, z, w: the shader's vec4 with .w scalar
        texel[c] = float(q.real[c]);
        texel[4 + c] = float(q.dual[c]);
      }
      if (t == 5) {
        const Mat3<double>& s = frames[f].scale[j];
        for (int row = 0; row < 3; ++row)
          for (int col = 0; col < 3; ++col) texel[8 + 4 * row + col] = float(s[col][row]);
      }
    }
  }
  return tex;
}

}  // namespace dqskin
