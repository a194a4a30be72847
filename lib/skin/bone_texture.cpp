// Packing JointTransforms into the BoneTexture layout of docs/DESIGN.md §4.1.
#include "dqskin/bone_texture.hpp"

#include <map>

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

std::vector<BoneTexture> pack_instance_textures(const Asset& asset, std::span<const MeshInstance> instances,
                                                std::span<const Pose> poses) {
  std::vector<BoneTexture> out(instances.size());
  std::map<int, size_t> packed;  // skin → the instance whose texture holds it
  for (size_t i = 0; i < instances.size(); ++i) {
    const MeshInstance& instance = instances[i];
    if (const auto it = packed.find(instance.skin); instance.skin >= 0 && it != packed.end()) {
      out[i] = out[it->second];
      continue;
    }
    std::vector<JointTransforms> frames;
    frames.reserve(poses.size());
    for (const Pose& pose : poses) frames.push_back(instance_joint_transforms(asset, instance, pose));
    out[i] = pack_bone_texture(frames);
    if (instance.skin >= 0) packed.emplace(instance.skin, i);
  }
  return out;
}

}  // namespace dqskin
