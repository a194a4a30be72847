// Bone-texture profiles (bone_profiles.hpp): every layout read back as its shader reads it gives the joint
// matrices again; texels sit where each runtime looks for them; skinning from the texels is the blend the
// profile implies (the project's DQS and LBS from the CPU reference deformer, Cocos's DQS variant).
//
// Tolerances come from the texels being float: every stored component is rounded once (relative error
// 2^-24 ≈ 6e-8). Matrix layouts store the entries themselves, so each decoded entry is within half a float
// ulp of the exact one. The DQ layouts rebuild entries from products and sums of a few rounded
// components (rotation by a normalized quaternion, t = 2 dual real*), so a decoded entry may be off by a
// few ulps of the largest entry: kDqTolerance is 4 (the worst seen is about 1.2).
#include "bone_profiles.hpp"

#include "dqskin/animation.hpp"
#include "dqskin/bone_texture.hpp"
#include "dqskin/load.hpp"
#include "../math/test_support.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace dqskin {
namespace {

using DVec3 = Vec3<double>;
using DVec4 = glm::vec<4, double, glm::defaultp>;

constexpr BoneProfile kAll[] = {BoneProfile::kDq, BoneProfile::kDqCocos, BoneProfile::kMat3x4, BoneProfile::kMat4};
constexpr double kFloatUlp = 0x1p-24;      // half an ulp of 1 in float: the relative rounding of a texel
constexpr double kDqTolerance = 4 * 0x1p-24;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The JointTransforms that joint_transforms would give for these joint matrices.
JointTransforms transforms_of(const std::vector<Mat4<double>>& matrices) {
  JointTransforms out;
  for (const Mat4<double>& m : matrices) {
    const JointSplit<double> split = split_joint_matrix(m);
    out.matrices.push_back(m);
    out.rigid.push_back(split.rigid);
    out.scale.push_back(split.scale);
    out.any_non_rigid = out.any_non_rigid || !split.is_rigid;
  }
  return out;
}

// Translate · rotate · scale, the glTF node order: no shear.
Mat4<double> trs(const DVec3& t, const Quat<double>& r, const DVec3& s) {
  return glm::translate(Mat4<double>(1.0), t) * Mat4<double>(glm::mat3_cast(r)) * glm::scale(Mat4<double>(1.0), s);
}

double largest_entry(const Mat4<double>& m) {
  double out = 0;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out = std::max(out, std::abs(m[c][r]));
  return out;
}

// Largest entry difference; infinity for NaN so that it never passes.
double max_diff(const Mat4<double>& a, const Mat4<double>& b) {
  double out = 0;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      const double d = std::abs(a[c][r] - b[c][r]);
      if (!(d <= out)) out = std::isnan(d) ? kInfinity : d;
    }
  return out;
}

double max_diff(const DVec3& a, const DVec3& b) {
  const double d = glm::length(a - b);
  return std::isnan(d) ? kInfinity : d;
}

// Frames of random joint matrices: rigid, uniformly scaled, non-uniformly scaled (no shear) and mirrored
// (one negative axis), one kind per frame so that every kind also meets the T = 5 dq layout.
std::vector<JointTransforms> random_frames(unsigned seed, size_t joints) {
  test::Random rng(seed);
  std::vector<JointTransforms> frames;
  for (int kind = 0; kind < 4; ++kind) {
    for (int repeat = 0; repeat < 3; ++repeat) {
      std::vector<Mat4<double>> m;
      for (size_t j = 0; j < joints; ++j) {
        DVec3 s(1.0);
        if (kind == 1) s = DVec3(rng.uniform(0.5, 2));
        if (kind >= 2) s = DVec3(rng.uniform(0.5, 2), rng.uniform(0.5, 2), rng.uniform(0.5, 2));
        if (kind == 3) s[int(j % 3)] = -s[int(j % 3)];
        m.push_back(trs(rng.vec3(10), rng.rotation(), s));
      }
      frames.push_back(transforms_of(m));
    }
  }
  return frames;
}

void expect_decodes_to_matrices(const BoneImage& image, std::span<const JointTransforms> frames,
                                const std::string& what) {
  for (size_t f = 0; f < frames.size(); ++f)
    for (size_t j = 0; j < image.joints; ++j) {
      const Mat4<double>& m = frames[f].matrices[j];
      const bool matrix_layout = image.profile == BoneProfile::kMat3x4 || image.profile == BoneProfile::kMat4;
      const double tolerance = (matrix_layout ? kFloatUlp : kDqTolerance) * std::max(1.0, largest_entry(m));
      EXPECT_LE(max_diff(decode_joint_matrix(image, j, f), m), tolerance)
          << what << " " << to_string(image.profile) << " frame " << f << " joint " << j;
    }
}

TEST(BoneProfiles, NamesRoundTripAndEachImpliesItsBlend) {
  std::set<std::string> texel_formulas, decode_formulas;
  for (BoneProfile p : kAll) {
    BoneProfile parsed = p == BoneProfile::kDq ? BoneProfile::kMat4 : BoneProfile::kDq;
    EXPECT_TRUE(parse_bone_profile(to_string(p), parsed)) << to_string(p);
    EXPECT_EQ(parsed, p);
    texel_formulas.insert(texel_formula(p));
    decode_formulas.insert(decode_formula(p));
  }
  EXPECT_EQ(texel_formulas.size(), 4u);  // one text each, none empty
  EXPECT_EQ(decode_formulas.size(), 4u);
  EXPECT_EQ(texel_formulas.count(""), 0u);
  BoneProfile untouched = BoneProfile::kMat3x4;
  for (const char* bad : {"", "DQ", "dq_cocos", "mat34", "mat4 "}) EXPECT_FALSE(parse_bone_profile(bad, untouched)) << bad;
  EXPECT_EQ(untouched, BoneProfile::kMat3x4);
  EXPECT_STREQ(implied_blend(BoneProfile::kDq), "dqs");
  EXPECT_STREQ(implied_blend(BoneProfile::kDqCocos), "dqs");
  EXPECT_STREQ(implied_blend(BoneProfile::kMat3x4), "lbs");
  EXPECT_STREQ(implied_blend(BoneProfile::kMat4), "lbs");
}

TEST(BoneProfiles, DqIsTheBoneTextureByteForByte) {
  for (size_t rigid_frames : {size_t(3), size_t(12)}) {  // all rigid (T = 2), then with scale (T = 5)
    const std::vector<JointTransforms> all = random_frames(7, 5);
    const std::span<const JointTransforms> frames(all.data(), rigid_frames);
    const BoneTexture expected = pack_bone_texture(frames);
    const BoneImage image = pack_bones(BoneProfile::kDq, frames);
    EXPECT_EQ(image.texels_per_joint, rigid_frames == 3 ? 2 : 5);
    EXPECT_EQ(image.texels_per_joint, expected.texels_per_joint);
    EXPECT_EQ(image.width, expected.width());
    EXPECT_EQ(image.height, frames.size());
    EXPECT_EQ(image.joints, 5u);
    EXPECT_EQ(image.frames, frames.size());
    EXPECT_EQ(image.rgba, expected.rgba);
  }
}

TEST(BoneProfiles, EmptyInputGivesAnEmptyImage) {
  for (BoneProfile p : kAll) {
    const BoneImage none = pack_bones(p, {});
    EXPECT_EQ(none.width * none.height, 0u) << to_string(p);
    EXPECT_TRUE(none.rgba.empty()) << to_string(p);
    const std::vector<JointTransforms> no_joints(2);
    const BoneImage empty = pack_bones(p, no_joints);
    EXPECT_TRUE(empty.rgba.empty()) << to_string(p);
    EXPECT_EQ(empty.frames, 0u) << to_string(p);
  }
}

TEST(BoneProfiles, RandomPosesDecodeToTheirJointMatrices) {
  const std::vector<JointTransforms> frames = random_frames(2024, 7);
  for (BoneProfile p : kAll) expect_decodes_to_matrices(pack_bones(p, frames), frames, "random");
}

// Shear is what Cocos's T·R·S cannot hold: the other layouts keep it, dq-cocos decodes R·diag(s) instead.
TEST(BoneProfiles, OnlyCocosLosesShear) {
  Mat4<double> shear(1.0);
  shear[1][0] = 0.4;  // x += 0.4 y
  const Mat4<double> m = trs(DVec3(1, 2, 3), glm::angleAxis(0.7, glm::normalize(DVec3(1, 1, 0))), DVec3(1.5, 1, 0.5)) * shear;
  const std::vector<JointTransforms> frames = {transforms_of({Mat4<double>(1.0), m})};
  for (BoneProfile p : {BoneProfile::kDq, BoneProfile::kMat3x4, BoneProfile::kMat4})
    expect_decodes_to_matrices(pack_bones(p, frames), frames, "sheared");
  const Mat4<double> cocos = decode_joint_matrix(pack_bones(BoneProfile::kDqCocos, frames), 1, 0);
  EXPECT_GT(max_diff(cocos, m), 0.05);
  EXPECT_LE(max_diff(DVec3(cocos[3]), DVec3(m[3])), kDqTolerance * largest_entry(m)) << "the translation survives";
  for (int i = 0; i < 3; ++i)  // each axis keeps its column's length
    EXPECT_NEAR(glm::length(DVec3(cocos[i])), glm::length(DVec3(m[i])), 1e-6) << "axis " << i;
}

// ---------------------------------------------------------------------------------------------------
// The project's rigs: joint matrices from the loader and sampler, as a bake would pack them.

struct RigFrames {
  Asset asset;
  MeshInstance instance;
  std::vector<Pose> poses;
  std::vector<JointTransforms> frames;
};

RigFrames rig_frames(const std::string& file) {
  RigFrames r{load_asset(std::string(DQSKIN_TESTDATA_DIR) + "/" + file), {}, {}, {}};
  for (const MeshInstance& inst : mesh_instances(r.asset, choose_scene(r.asset, -1)))
    if (inst.skin >= 0) r.instance = inst;
  EXPECT_GE(r.instance.skin, 0) << file;
  EXPECT_FALSE(r.asset.clips.empty()) << file;
  for (double t : {0.0, 0.3, 0.55, 0.8, 1.0}) {
    r.poses.push_back(sample_pose(r.asset, &r.asset.clips[0], t));
    r.frames.push_back(joint_transforms(r.asset.skins[size_t(r.instance.skin)], r.poses.back()));
  }
  return r;
}

bool has_shear(const JointTransforms& jt, size_t joint) {
  const Mat3<double>& s = jt.scale[joint];
  return std::max({std::abs(s[0][1]), std::abs(s[0][2]), std::abs(s[1][2])}) > 1e-9;
}

TEST(BoneProfiles, RigPosesDecodeToTheirJointMatrices) {
  for (const char* file : {"twisted_cylinder.gltf", "nonuniform_scale.gltf", "eight_influences.gltf"}) {
    const RigFrames rig = rig_frames(file);
    for (BoneProfile p : {BoneProfile::kDq, BoneProfile::kMat3x4, BoneProfile::kMat4})
      expect_decodes_to_matrices(pack_bones(p, rig.frames), rig.frames, file);
    // dq-cocos: the joints without shear (all of them in these rigs: scale sits on the scaled joint itself).
    const BoneImage cocos = pack_bones(BoneProfile::kDqCocos, rig.frames);
    size_t compared = 0, scaled = 0;
    for (size_t f = 0; f < rig.frames.size(); ++f)
      for (size_t j = 0; j < cocos.joints; ++j) {
        if (has_shear(rig.frames[f], j)) continue;
        const Mat4<double>& m = rig.frames[f].matrices[j];
        EXPECT_LE(max_diff(decode_joint_matrix(cocos, j, f), m), kDqTolerance * std::max(1.0, largest_entry(m)))
            << file << " dq-cocos frame " << f << " joint " << j;
        ++compared;
        if (!split_joint_matrix(m).is_rigid) ++scaled;
      }
    EXPECT_EQ(compared, rig.frames.size() * cocos.joints) << file;
    if (std::string(file) == "nonuniform_scale.gltf") {
      EXPECT_GT(scaled, 0u) << "the rig should scale a joint";
    }
  }
}

// ---------------------------------------------------------------------------------------------------
// Texel placement, by hand: 2 joints × 2 frames.

// Frame 0: both joints turned the same way. Frame 1: joint 0 turned 160° about +x, joint 1 160° about −x,
// so that their real parts (each with w ≥ 0) point into opposite hemispheres.
std::vector<JointTransforms> two_by_two() {
  const DVec3 x(1, 0, 0);
  const double a = glm::radians(160.0);
  return {transforms_of({trs(DVec3(1, 2, 3), glm::angleAxis(0.3, x), DVec3(1)),
                         trs(DVec3(-4, 5, 6), glm::angleAxis(0.5, x), DVec3(1))}),
          transforms_of({trs(DVec3(7, 8, 9), glm::angleAxis(a, x), DVec3(1)),
                         trs(DVec3(0.5, -1.5, 2.5), glm::angleAxis(-a, x), DVec3(2, 0.5, 1))})};
}

DVec4 texel(const BoneImage& image, size_t x, size_t y) {
  EXPECT_LT(x, image.width);
  EXPECT_LT(y, image.height);
  if (x >= image.width || y >= image.height) return DVec4(std::numeric_limits<double>::quiet_NaN());
  const float* t = &image.rgba[4 * (y * image.width + x)];
  return DVec4(t[0], t[1], t[2], t[3]);
}

DVec4 as_float(const DVec4& v) { return DVec4(glm::vec4(v)); }

TEST(BoneProfiles, Mat4TexelsAreColumnsWithATrailingIdentity) {
  const std::vector<JointTransforms> frames = two_by_two();
  const BoneImage image = pack_bones(BoneProfile::kMat4, frames);
  EXPECT_EQ(image.width, 12u);  // (2 joints + 1) × 4
  EXPECT_EQ(image.height, 2u);
  EXPECT_EQ(image.texels_per_joint, 4);
  EXPECT_EQ(image.rgba.size(), 12u * 2u * 4u);
  // Bottom-up: frame 1 in row 0, frame 0 in the last row (Babylon's EXR reader flips them back).
  const Mat4<double>& m11 = frames[1].matrices[1];
  EXPECT_EQ(texel(image, 4 * 1 + 3, 0), as_float(DVec4(0.5, -1.5, 2.5, 1)));  // translation, w = 1
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(texel(image, 4 * 1 + size_t(k), 0), as_float(m11[k])) << "column " << k;
    EXPECT_EQ(texel(image, size_t(k), 1), as_float(frames[0].matrices[0][k])) << "column " << k;
  }
  for (size_t f = 0; f < 2; ++f)
    for (int k = 0; k < 4; ++k) EXPECT_EQ(texel(image, 8 + size_t(k), f), Mat4<double>(1.0)[k]) << "identity, frame " << f;
}

// Bottom-up frames keep a clip's rows together: frames 0 … a−1 then a … n−1 in one image are the second
// clip's own image above the first's, bit for bit, so a combined texture's clip starts at image row
// n − first_frame − frame_count (bone_writer.cpp's clip table).
TEST(BoneProfiles, Mat4ClipsStackBottomUp) {
  const std::vector<JointTransforms> all = random_frames(7, 3);
  const size_t split = 5;
  const std::span<const JointTransforms> frames(all);
  const BoneImage whole = pack_bones(BoneProfile::kMat4, frames);
  const BoneImage first = pack_bones(BoneProfile::kMat4, frames.first(split));
  const BoneImage second = pack_bones(BoneProfile::kMat4, frames.subspan(split));
  ASSERT_EQ(whole.height, first.height + second.height);
  const size_t row = 4 * whole.width;  // floats a row
  const auto rows = [&](size_t y, size_t count) {
    const auto begin = whole.rgba.begin() + std::ptrdiff_t(y * row);
    return std::vector<float>(begin, begin + std::ptrdiff_t(count * row));
  };
  EXPECT_EQ(rows(whole.height - split, split), first.rgba);  // the first clip at the bottom
  EXPECT_EQ(rows(0, second.height), second.rgba);
}

TEST(BoneProfiles, Mat3x4TexelsAreRows) {
  const std::vector<JointTransforms> frames = two_by_two();
  const BoneImage image = pack_bones(BoneProfile::kMat3x4, frames);
  EXPECT_EQ(image.width, 6u);
  EXPECT_EQ(image.height, 2u);
  EXPECT_EQ(image.texels_per_joint, 3);
  for (size_t f = 0; f < 2; ++f)
    for (size_t j = 0; j < 2; ++j) {
      const Mat4<double>& m = frames[f].matrices[j];
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(texel(image, 3 * j + size_t(k), f), as_float(DVec4(m[0][k], m[1][k], m[2][k], m[3][k])))
            << "frame " << f << " joint " << j << " row " << k;
    }
  EXPECT_EQ(texel(image, 3 * 1 + 0, 1).w, 0.5f);  // t.x of joint 1, frame 1
  EXPECT_EQ(texel(image, 3 * 1 + 0, 1).x, 2.0);  // its x scale: the turn about x leaves that axis alone
}

TEST(BoneProfiles, DqTexelsAreRealThenDual) {
  const std::vector<JointTransforms> frames = two_by_two();
  const BoneImage image = pack_bones(BoneProfile::kDq, frames);
  ASSERT_EQ(image.texels_per_joint, 5);  // joint 1 of frame 1 is scaled
  EXPECT_EQ(image.width, 10u);
  const DualQuat<double>& q = frames[1].rigid[1];
  EXPECT_EQ(texel(image, 5 * 1 + 0, 1), as_float(DVec4(q.real.x, q.real.y, q.real.z, q.real.w)));
  EXPECT_EQ(texel(image, 5 * 1 + 1, 1), as_float(DVec4(q.dual.x, q.dual.y, q.dual.z, q.dual.w)));
  EXPECT_EQ(texel(image, 5 * 1 + 3, 1).w, 0.0);  // S rows have w = 0
}

TEST(BoneProfiles, CocosTexelsRunLinearlyWithTheSignOfJointZero) {
  const std::vector<JointTransforms> frames = two_by_two();
  const BoneImage image = pack_bones(BoneProfile::kDqCocos, frames);
  EXPECT_EQ(image.width, 12u);  // 12 texels: the smallest side, a multiple of 12
  EXPECT_EQ(image.height, 12u);
  EXPECT_EQ(image.texels_per_joint, 3);
  // Frame 1's real parts are in opposite hemispheres: joint 1 is stored negated, both parts.
  ASSERT_LT(glm::dot(frames[1].rigid[0].real, frames[1].rigid[1].real), 0);
  ASSERT_GT(glm::dot(frames[0].rigid[0].real, frames[0].rigid[1].real), 0);
  for (size_t f = 0; f < 2; ++f)
    for (size_t j = 0; j < 2; ++j) {
      const double sign = f == 1 && j == 1 ? -1 : 1;
      const DualQuat<double>& q = frames[f].rigid[j];
      const size_t i = 3 * (f * 2 + j);  // one row holds everything
      EXPECT_EQ(texel(image, i, 0), as_float(sign * DVec4(q.real.x, q.real.y, q.real.z, q.real.w))) << f << j;
      EXPECT_EQ(texel(image, i + 1, 0), as_float(sign * DVec4(q.dual.x, q.dual.y, q.dual.z, q.dual.w))) << f << j;
    }
  EXPECT_EQ(texel(image, 3 * 3 + 2, 0), as_float(DVec4(2, 0.5, 1, 0)));  // frame 1 joint 1: its axes' scale
  EXPECT_EQ(texel(image, 2, 0), as_float(DVec4(1, 1, 1, 0)));
  for (size_t i = 12 * 4; i < image.rgba.size(); ++i) ASSERT_EQ(image.rgba[i], 0.0f) << "padding at float " << i;
  // Negating both parts is the same pose: the decoded matrix is still joint 1's.
  EXPECT_LE(max_diff(decode_joint_matrix(image, 1, 1), frames[1].matrices[1]),
            kDqTolerance * largest_entry(frames[1].matrices[1]));
}

// Joints without translation have an all-zero dual part, and negating it makes −0: Cocos writes +0.
TEST(BoneProfiles, CocosStoresPositiveZeros) {
  const DVec3 x(1, 0, 0);
  const double a = glm::radians(160.0);
  const std::vector<JointTransforms> frames = {
      transforms_of({trs(DVec3(0), glm::angleAxis(a, x), DVec3(1)), trs(DVec3(0), glm::angleAxis(-a, x), DVec3(1))})};
  const BoneImage image = pack_bones(BoneProfile::kDqCocos, frames);
  EXPECT_EQ(texel(image, 4, 0), DVec4(0)) << "joint 1's dual part";
  for (float v : image.rgba) EXPECT_FALSE(v == 0 && std::signbit(v)) << "Cocos stores +0 for -0";
  EXPECT_LT(texel(image, 3, 0).w, 0) << "joint 1 is negated: its real part turned towards joint 0's";
}

TEST(BoneProfiles, CocosRowsWrapAtAMultipleOfTwelve) {
  const std::vector<JointTransforms> frames = random_frames(99, 7);  // 12 frames × 7 joints × 3 = 252 texels
  const BoneImage image = pack_bones(BoneProfile::kDqCocos, frames);
  EXPECT_EQ(image.width, 24u);  // sqrt(252) ≈ 15.9, rounded up to a multiple of 12
  EXPECT_EQ(image.height, 24u);
  EXPECT_EQ(image.width % 12, 0u);
  // The last joint of the last frame starts at texel 249: column 9 of row 10.
  const DualQuat<double>& q = frames[11].rigid[6];
  const double sign = glm::dot(q.real, frames[11].rigid[0].real) < 0 ? -1 : 1;
  EXPECT_EQ(texel(image, 249 % 24, 249 / 24), as_float(sign * DVec4(q.real.x, q.real.y, q.real.z, q.real.w)));
  expect_decodes_to_matrices(image, frames, "wrapped");
}

// ---------------------------------------------------------------------------------------------------
// skin_vertex against the CPU reference deformer on the rigs, every vertex of every sampled frame.

struct VertexInfluences {
  std::vector<int> joints;
  std::vector<float> weights;
};

VertexInfluences influences_of(const Primitive& prim, size_t v) {
  VertexInfluences out;
  for (size_t k = 0; k < size_t(prim.influences); ++k) {
    out.joints.push_back(int(prim.joints[v * size_t(prim.influences) + k]));
    out.weights.push_back(prim.weights[v * size_t(prim.influences) + k]);
  }
  return out;
}

struct Worst {
  double position = 0, normal = 0;
  void take(double p, double n) {
    position = std::isnan(p) ? kInfinity : std::max(position, p);
    normal = std::isnan(n) ? kInfinity : std::max(normal, n);
  }
};

// The candy wrapper's middle ring under LBS has a zero normal (the 3×3 is singular there): it stays zero.
DVec3 unit_or_zero(const DVec3& v) {
  const double length = glm::length(v);
  return length > 0 ? v / length : v;
}

// About one float ulp at the rigs' largest coordinate (4.5: ulp 4.8e-7) and at 1 for unit normals
// (1.2e-7); the worst seen are 1.3e-7 and 3.2e-8.
constexpr double kPositionTolerance = 5e-7, kNormalTolerance = 1.2e-7;

TEST(BoneProfiles, SkinVertexDqIsTheProjectsDqs) {
  for (const char* file : {"twisted_cylinder.gltf", "nonuniform_scale.gltf", "eight_influences.gltf"}) {
    const RigFrames rig = rig_frames(file);
    const BoneImage image = pack_bones(BoneProfile::kDq, rig.frames);
    const Primitive& prim = rig.asset.meshes[size_t(rig.instance.mesh)].primitives[0];
    Worst worst;
    for (size_t f = 0; f < rig.frames.size(); ++f) {
      const DeformedPrimitive expected =
          deform_primitive(rig.asset, rig.instance, 0, rig.poses[f], &rig.frames[f], BlendMode::kDqs);
      for (size_t v = 0; v < prim.vertex_count(); ++v) {
        const VertexInfluences in = influences_of(prim, v);
        const SkinnedVertex got = skin_vertex(image, f, in.joints, in.weights, DVec3(prim.positions[v]), DVec3(prim.normals[v]));
        worst.take(max_diff(got.position, expected.positions[v]), max_diff(got.normal, expected.normals[v]));
      }
    }
    EXPECT_LE(worst.position, kPositionTolerance) << file;
    EXPECT_LE(worst.normal, kNormalTolerance) << file;
  }
}

TEST(BoneProfiles, SkinVertexMatrixProfilesAreLbs) {
  for (const char* file : {"twisted_cylinder.gltf", "nonuniform_scale.gltf", "eight_influences.gltf"}) {
    const RigFrames rig = rig_frames(file);
    const Primitive& prim = rig.asset.meshes[size_t(rig.instance.mesh)].primitives[0];
    for (BoneProfile p : {BoneProfile::kMat3x4, BoneProfile::kMat4}) {
      const BoneImage image = pack_bones(p, rig.frames);
      Worst worst;
      for (size_t f = 0; f < rig.frames.size(); ++f) {
        const DeformedPrimitive expected =
            deform_primitive(rig.asset, rig.instance, 0, rig.poses[f], &rig.frames[f], BlendMode::kLbs);
        for (size_t v = 0; v < prim.vertex_count(); ++v) {
          const VertexInfluences in = influences_of(prim, v);
          const SkinnedVertex got = skin_vertex(image, f, in.joints, in.weights, DVec3(prim.positions[v]), DVec3(prim.normals[v]));
          // The runtimes turn normals by the blended 3×3 itself (the reference uses its cofactor).
          Mat3<double> a(0.0);
          for (size_t k = 0; k < in.joints.size(); ++k)
            a += Mat3<double>(rig.frames[f].matrices[size_t(in.joints[k])]) * double(in.weights[k]);
          worst.take(max_diff(got.position, expected.positions[v]),
                     max_diff(got.normal, unit_or_zero(a * DVec3(prim.normals[v]))));
        }
      }
      EXPECT_LE(worst.position, kPositionTolerance) << file << " " << to_string(p);
      EXPECT_LE(worst.normal, kNormalTolerance) << file << " " << to_string(p);
    }
  }
}

TEST(BoneProfiles, SkinVertexCocosEqualsDqOnRigidPoses) {
  for (const char* file : {"twisted_cylinder.gltf", "bending_arm.gltf", "eight_influences.gltf"}) {
    const RigFrames rig = rig_frames(file);
    for (const JointTransforms& jt : rig.frames) ASSERT_FALSE(jt.any_non_rigid) << file;
    const BoneImage dq = pack_bones(BoneProfile::kDq, rig.frames), cocos = pack_bones(BoneProfile::kDqCocos, rig.frames);
    const Primitive& prim = rig.asset.meshes[size_t(rig.instance.mesh)].primitives[0];
    Worst worst;
    double moved = 0;
    for (size_t f = 0; f < rig.frames.size(); ++f)
      for (size_t v = 0; v < prim.vertex_count(); ++v) {
        const VertexInfluences in = influences_of(prim, v);
        const DVec3 p(prim.positions[v]), n(prim.normals[v]);
        const SkinnedVertex a = skin_vertex(dq, f, in.joints, in.weights, p, n);
        const SkinnedVertex b = skin_vertex(cocos, f, in.joints, in.weights, p, n);
        worst.take(max_diff(a.position, b.position), max_diff(a.normal, b.normal));
        moved = std::max(moved, glm::length(a.position - p));
      }
    EXPECT_GT(moved, 0.1) << file << ": the clip should move the mesh";
    EXPECT_LE(worst.position, kPositionTolerance) << file;
    EXPECT_LE(worst.normal, kNormalTolerance) << file;
  }
}

// skin.comp divides the weights by their sum; so does the dq profile, scale included.
TEST(BoneProfiles, SkinVertexDqDividesWeightsByTheirSum) {
  const std::vector<JointTransforms> frames = two_by_two();
  const BoneImage image = pack_bones(BoneProfile::kDq, frames);
  const int joints[] = {0, 1};
  const float partial[] = {0.5f, 0.25f}, whole[] = {2.0f / 3, 1.0f / 3};
  const DVec3 p(0.3, -0.2, 0.9), n(0, 0, 1);
  const SkinnedVertex a = skin_vertex(image, 1, joints, partial, p, n), b = skin_vertex(image, 1, joints, whole, p, n);
  EXPECT_LE(max_diff(a.position, b.position), kPositionTolerance);
  EXPECT_LE(max_diff(a.normal, b.normal), kNormalTolerance);
  const float none[] = {0.0f, 0.0f};
  EXPECT_EQ(skin_vertex(image, 1, joints, none, p, n).position, p) << "no weight: the vertex stays";
}

// Under non-uniform scale Cocos turns normals by R alone, where dq applies the scale's cofactor first:
// the two profiles must then disagree on normals (and agree on positions, both being R (S p) + t for
// one influence).
TEST(BoneProfiles, SkinVertexCocosLeavesNormalsUnscaled) {
  const std::vector<JointTransforms> frames = two_by_two();
  const BoneImage dq = pack_bones(BoneProfile::kDq, frames), cocos = pack_bones(BoneProfile::kDqCocos, frames);
  const int joint[] = {1};
  const float weight[] = {1.0f};
  const DVec3 p(0.3, -0.2, 0.9), n = glm::normalize(DVec3(1, 1, 0));
  const SkinnedVertex a = skin_vertex(dq, 1, joint, weight, p, n), b = skin_vertex(cocos, 1, joint, weight, p, n);
  EXPECT_LE(max_diff(a.position, b.position), kPositionTolerance);
  EXPECT_LE(max_diff(a.position, DVec3(frames[1].matrices[1] * DVec4(p, 1))), kPositionTolerance);
  const DVec3 rotated_only = frames[1].rigid[1].real * n;
  EXPECT_LE(max_diff(b.normal, rotated_only), kNormalTolerance);
  EXPECT_GT(max_diff(a.normal, b.normal), 0.1);
}

}  // namespace
}  // namespace dqskin
