// The palette and pack stages for a batch of poses, on the CPU (pack_instance_textures): what the GPU
// deformer uploads, checked without a GPU.
#include "dqskin/bone_texture.hpp"

#include "dqskin/animation.hpp"
#include "dqskin/load.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace dqskin {
namespace {

// two_skins.gltf: node 0 draws mesh 0 with skin 0, node 1 mesh 1 with skin 1. Extra instances make the
// two cases no rig has: a second instance of skin 0, and node 1 drawing its mesh rigidly.
TEST(PackInstanceTextures, SharedSkinsShareATextureAndRigidInstancesAreOneJoint) {
  const Asset asset = load_asset(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf");
  ASSERT_FALSE(asset.clips.empty());
  const std::vector<MeshInstance> instances = {{0, 0, 0}, {1, 1, 1}, {1, 1, 0}, {1, 1, -1}};
  std::vector<Pose> poses;
  for (double t : {0.0, 0.4, 0.9}) poses.push_back(sample_pose(asset, &asset.clips[0], t));
  const std::vector<BoneTexture> textures = pack_instance_textures(asset, instances, poses);
  ASSERT_EQ(textures.size(), instances.size());

  for (size_t i : {size_t(0), size_t(1)}) {  // each skin: the packed palette of that skin
    std::vector<JointTransforms> frames;
    for (const Pose& pose : poses) frames.push_back(joint_transforms(asset.skins[size_t(instances[i].skin)], pose));
    const BoneTexture expected = pack_bone_texture(frames);
    EXPECT_EQ(textures[i].rgba, expected.rgba) << "instance " << i;
    EXPECT_EQ(textures[i].frames, poses.size());
  }
  EXPECT_EQ(textures[2].rgba, textures[0].rgba);  // skin 0 again: the same texture
  EXPECT_NE(textures[1].rgba, textures[0].rgba);

  // The rigid instance: one joint whose joint matrix is node 1's world matrix at each pose.
  const BoneTexture& rigid = textures[3];
  ASSERT_EQ(rigid.joints, 1u);
  ASSERT_EQ(rigid.frames, poses.size());
  for (size_t f = 0; f < poses.size(); ++f) {
    const DualQuat<double> q = split_joint_matrix(poses[f].world[1]).rigid;
    const float* texel = &rigid.rgba[f * rigid.width() * 4];
    for (int c = 0; c < 4; ++c) {
      EXPECT_EQ(texel[c], float(q.real[c])) << "frame " << f;
      EXPECT_EQ(texel[4 + c], float(q.dual[c])) << "frame " << f;
    }
  }
}

}  // namespace
}  // namespace dqskin
