// Properties of the CPU reference deformer (skinning.hpp), checked on the project's synthetic rigs
// (testdata/, written by scripts/testdata/make_rigs.py) and, where present, on the shared sample models.
//
// The rigs' rest poses are pure translations whose inverse bind matrices are their exact inverses, so
// at rest every joint matrix is the identity in exact arithmetic; tolerances are relative to the
// bounding-box diagonal of the model.
#include "dqskin/animation.hpp"
#include "dqskin/load.hpp"
#include "dqskin/skinning.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using DVec3 = Vec3<double>;
using DVec4 = glm::vec<4, double, glm::defaultp>;

constexpr BlendMode kModes[] = {BlendMode::kLbs, BlendMode::kDqs, BlendMode::kDib};

// The rigs scripts/testdata/make_rigs.py writes into testdata/.
const char* const kRigs[] = {"twisted_cylinder.gltf", "bending_arm.gltf",        "uniform_scale.gltf",
                             "nonuniform_scale.gltf", "eight_influences.gltf",   "interpolation_modes.gltf",
                             "morph_skin.gltf",       "two_skins.gltf"};

// Skinned shared sample models, relative to DQSKIN_SHARED_TESTDATA_DIR.
const char* const kSharedSkinned[] = {"RiggedSimple/RiggedSimple.glb", "CesiumMan/CesiumMan.glb", "Fox/Fox.glb",
                                      "raylib_robot/robot.glb", "SimpleSkin/SimpleSkin.gltf"};

struct Model {
  std::string name;
  Asset asset;
  std::vector<MeshInstance> skinned;  // the skinned instances of the default scene
  double diagonal = 0;                // bounding-box diagonal of their bind positions
};

Model make_model(const std::string& name, Asset asset) {
  Model m{name, std::move(asset), {}, 0};
  for (const MeshInstance& inst : mesh_instances(m.asset, choose_scene(m.asset, -1)))
    if (inst.skin >= 0) m.skinned.push_back(inst);
  DVec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const MeshInstance& inst : m.skinned)
    for (const Primitive& p : m.asset.meshes[size_t(inst.mesh)].primitives)
      for (const glm::vec3& v : p.positions) lo = glm::min(lo, DVec3(v)), hi = glm::max(hi, DVec3(v));
  m.diagonal = m.skinned.empty() ? 1.0 : glm::length(hi - lo);
  return m;
}

const Model& rig(const std::string& file) {
  static std::map<std::string, Model> cache;
  auto it = cache.find(file);
  if (it == cache.end())
    it = cache.emplace(file, make_model(file, load_asset((fs::path(DQSKIN_TESTDATA_DIR) / file).string()))).first;
  return it->second;
}

const fs::path kSharedDir = DQSKIN_SHARED_TESTDATA_DIR;

bool have_shared() { return fs::is_directory(kSharedDir); }

std::string shared_missing_reason() {
  return "the shared sample models are not present at " + kSharedDir.string() +
         " (DQSKIN_SHARED_TESTDATA_DIR); only the project's rigs were checked";
}

// The shared skinned models that exist (a listed model that is missing fails the calling test).
std::vector<const Model*> shared_models() {
  static std::map<std::string, Model> cache;
  std::vector<const Model*> out;
  for (const char* rel : kSharedSkinned) {
    auto it = cache.find(rel);
    if (it == cache.end()) {
      const fs::path path = kSharedDir / rel;
      if (!fs::exists(path)) {
        ADD_FAILURE() << "shared model " << path << " is missing";
        continue;
      }
      it = cache.emplace(rel, make_model(rel, load_asset(path.string()))).first;
    }
    out.push_back(&it->second);
  }
  return out;
}

std::vector<const Model*> all_rigs() {
  std::vector<const Model*> out;
  for (const char* f : kRigs) out.push_back(&rig(f));
  return out;
}

// Joint matrix j of `skin` at `pose`, computed here: world(joint) · inverseBind(joint).
Mat4<double> joint_matrix(const Skin& skin, const Pose& pose, size_t j) {
  return pose.world[size_t(skin.joints[j])] * skin.inverse_bind[j];
}

double max_abs(const Mat4<double>& m) {
  double out = 0;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out = std::max(out, std::abs(m[c][r]));
  return out;
}

DVec3 apply(const Mat4<double>& m, const DVec3& p) { return DVec3(m * DVec4(p, 1)); }

// det(A) · A⁻ᵀ: maps normals.
Mat3<double> cofactor(const Mat3<double>& a) {
  return Mat3<double>(glm::cross(a[1], a[2]), glm::cross(a[2], a[0]), glm::cross(a[0], a[1]));
}

// Position and normal of vertex v after the morph targets (weights from the pose), before skinning.
DVec3 morphed_position(const Primitive& p, const std::vector<double>& w, size_t v) {
  DVec3 out(p.positions[v]);
  for (size_t k = 0; k < w.size() && k < p.targets.size(); ++k)
    if (!p.targets[k].positions.empty()) out += w[k] * DVec3(p.targets[k].positions[v]);
  return out;
}

DVec3 morphed_normal(const Primitive& p, const std::vector<double>& w, size_t v) {
  DVec3 out(p.normals[v]);
  for (size_t k = 0; k < w.size() && k < p.targets.size(); ++k)
    if (!p.targets[k].normals.empty()) out += w[k] * DVec3(p.targets[k].normals[v]);
  return out;
}

// The vertex's non-zero influences (skin joint index, weight), weights divided by their sum.
std::vector<std::pair<size_t, double>> influences(const Primitive& p, size_t v) {
  std::vector<std::pair<size_t, double>> out;
  double sum = 0;
  for (size_t k = 0; k < size_t(p.influences); ++k) {
    const double w = double(p.weights[v * size_t(p.influences) + k]);
    if (w > 0) out.emplace_back(p.joints[v * size_t(p.influences) + k], w), sum += w;
  }
  for (auto& [j, w] : out) w /= sum;
  return out;
}

// Index of the only joint that moves v, or -1 when v has none or several.
int single_joint(const Primitive& p, size_t v) {
  const auto in = influences(p, v);
  return in.size() == 1 ? int(in[0].first) : -1;
}

// Deforms every skinned instance of the model at `pose`: [instance][primitive].
std::vector<std::vector<DeformedPrimitive>> deform_all(const Model& m, const Pose& pose, BlendMode mode) {
  std::vector<std::vector<DeformedPrimitive>> out;
  for (const MeshInstance& inst : m.skinned) {
    const JointTransforms jt = joint_transforms(m.asset.skins[size_t(inst.skin)], pose);
    out.emplace_back();
    for (size_t p = 0; p < m.asset.meshes[size_t(inst.mesh)].primitives.size(); ++p)
      out.back().push_back(deform_primitive(m.asset, inst, p, pose, &jt, mode));
  }
  return out;
}

const Clip& clip_named(const Asset& asset, const std::string& name) {
  for (const Clip& c : asset.clips)
    if (c.name == name) return c;
  ADD_FAILURE() << "no clip named " << name;
  static const Clip none;
  return none;
}

const Primitive& only_primitive(const Model& m) { return m.asset.meshes[size_t(m.skinned.at(0).mesh)].primitives.at(0); }

std::string str(const DVec3& v) {
  std::ostringstream s;
  s << std::setprecision(17) << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

// Five times spread over the clip, ends included.
std::vector<double> some_times(const Clip& clip) {
  std::vector<double> t;
  for (int i = 0; i <= 4; ++i) t.push_back(clip.first_key + (clip.last_key - clip.first_key) * i / 4.0);
  return t;
}

// ---------------------------------------------------------------------------------------------------
// Rest pose

// Checks that deforming `m` at its rest pose leaves every vertex at its (morphed) bind position;
// `tolerance` is relative to the diagonal for positions, absolute for unit normals.
void expect_rest_pose_is_bind_pose(const Model& m, double tolerance) {
  const Pose rest = sample_pose(m.asset, nullptr, 0);
  for (BlendMode mode : kModes) {
    const auto out = deform_all(m, rest, mode);
    size_t checked = 0;
    double worst_p = 0, worst_n = 0;
    for (size_t i = 0; i < m.skinned.size(); ++i) {
      const MeshInstance& inst = m.skinned[i];
      const std::vector<double>& w = rest.weights[size_t(inst.node)];
      for (size_t pi = 0; pi < out[i].size(); ++pi) {
        const Primitive& prim = m.asset.meshes[size_t(inst.mesh)].primitives[pi];
        for (size_t v = 0; v < prim.vertex_count(); ++v, ++checked) {
          worst_p = std::max(worst_p, glm::length(out[i][pi].positions[v] - morphed_position(prim, w, v)) / m.diagonal);
          if (!prim.normals.empty())
            worst_n = std::max(worst_n, glm::length(out[i][pi].normals[v] - glm::normalize(morphed_normal(prim, w, v))));
        }
      }
    }
    EXPECT_GT(checked, 0u) << m.name;
    EXPECT_LE(worst_p, tolerance) << m.name << " " << to_string(mode) << ": positions moved at rest";
    EXPECT_LE(worst_n, tolerance) << m.name << " " << to_string(mode) << ": normals turned at rest";
  }
}

TEST(CpuDeform, EveryGeneratedRigIsInTestdata) {
  for (const char* name : kRigs)
    EXPECT_TRUE(fs::is_regular_file(fs::path(DQSKIN_TESTDATA_DIR) / name))
        << name << " is missing from testdata/: run python3 scripts/testdata/make_rigs.py";
}

TEST(CpuDeform, BindPoseLeavesEveryVertexInPlace) {
  for (const Model* m : all_rigs()) {
    SCOPED_TRACE(m->name);
    // The generator's promise that this test relies on: at rest every joint matrix is exactly I.
    const Pose rest = sample_pose(m->asset, nullptr, 0);
    for (const Skin& skin : m->asset.skins)
      for (size_t j = 0; j < skin.joints.size(); ++j)
        EXPECT_EQ(max_abs(joint_matrix(skin, rest, j) - Mat4<double>(1.0)), 0.0) << "joint " << j << " of skin " << skin.name;
    expect_rest_pose_is_bind_pose(*m, 1e-9);
  }
}

// Shared models: only those whose inverse bind matrices invert their rest pose (not promised by glTF;
// many files are exported with the bind pose differing from the rest pose). The tolerance follows how
// far from I the rest joint matrices are (float32 data).
TEST(CpuDeformShared, BindPoseLeavesEveryVertexInPlace) {
  if (!have_shared()) GTEST_SKIP() << shared_missing_reason();
  size_t checked = 0;
  for (const Model* m : shared_models()) {
    const Pose rest = sample_pose(m->asset, nullptr, 0);
    double deviation = 0;  // largest |M − I| entry, translations relative to the diagonal
    for (const Skin& skin : m->asset.skins)
      for (size_t j = 0; j < skin.joints.size(); ++j) {
        const Mat4<double> d = joint_matrix(skin, rest, j) - Mat4<double>(1.0);
        for (int c = 0; c < 4; ++c)
          for (int r = 0; r < 3; ++r) deviation = std::max(deviation, std::abs(d[c][r]) / (c == 3 ? m->diagonal : 1.0));
      }
    if (deviation > 1e-5) {
      std::cout << "  " << m->name << ": not checked, its inverse bind matrices do not invert the rest pose "
                << "(a rest joint matrix differs from I by " << deviation << ")\n";
      continue;
    }
    std::cout << "  " << m->name << ": rest joint matrices within " << deviation << " of I, checked\n";
    SCOPED_TRACE(m->name);
    expect_rest_pose_is_bind_pose(*m, std::max(1e-9, 20 * deviation));
    ++checked;
  }
  RecordProperty("shared_models_checked", std::to_string(checked));
  if (checked == 0) GTEST_SKIP() << "no shared model has inverse bind matrices that invert its rest pose";
}

// ---------------------------------------------------------------------------------------------------
// Vertices moved by one joint

// How far joint matrix m is from rigid, as docs/DESIGN.md §3.6 measures it (largest entry of S − I in A = R S),
// to first order: half the largest entry of AᵀA − I.
double rigidity_defect(const Mat4<double>& m) {
  const Mat3<double> a(m);
  const Mat3<double> d = glm::transpose(a) * a - Mat3<double>(1.0);
  double out = 0;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) out = std::max(out, std::abs(d[c][r]));
  return out / 2;
}

// At several frames of the first clip, vertices with one influence are placed identically by all modes.
// A joint whose scale or shear is within docs/DESIGN.md §3.6's 1e-5 counts as rigid, so DQS drops its S (at most
// that far from I) where LBS keeps it: such vertices may differ by |(S − I) v| ≤ 3 ε |v|, and their
// normals by a few ε; the generated rigs have ε ≈ 1e-16. Returns how many vertices were compared.
size_t expect_single_influence_agreement(const Model& m) {
  if (m.asset.clips.empty()) return 0;
  const Clip& clip = m.asset.clips.front();
  size_t compared = 0;
  double largest_defect = 0;
  for (double t : some_times(clip)) {
    const Pose pose = sample_pose(m.asset, &clip, t);
    const auto lbs = deform_all(m, pose, BlendMode::kLbs);
    for (BlendMode mode : {BlendMode::kDqs, BlendMode::kDib}) {
      const auto out = deform_all(m, pose, mode);
      double worst_p = 0, worst_n = 0;  // beyond what a dropped near-identity S explains
      for (size_t i = 0; i < m.skinned.size(); ++i) {
        const Skin& skin = m.asset.skins[size_t(m.skinned[i].skin)];
        const std::vector<double>& w = pose.weights[size_t(m.skinned[i].node)];
        for (size_t pi = 0; pi < out[i].size(); ++pi) {
          const Primitive& prim = m.asset.meshes[size_t(m.skinned[i].mesh)].primitives[pi];
          for (size_t v = 0; v < prim.vertex_count(); ++v) {
            const int j = single_joint(prim, v);
            if (j < 0) continue;
            ++compared;
            double eps = rigidity_defect(joint_matrix(skin, pose, size_t(j)));
            eps = eps <= 1.01e-5 ? eps : 0;  // beyond it, both modes apply S
            largest_defect = std::max(largest_defect, eps);
            const double allowed = 3 * eps * glm::length(morphed_position(prim, w, v));
            worst_p = std::max(worst_p, (glm::length(out[i][pi].positions[v] - lbs[i][pi].positions[v]) - allowed) / m.diagonal);
            if (!prim.normals.empty())
              worst_n = std::max(worst_n, glm::length(out[i][pi].normals[v] - lbs[i][pi].normals[v]) - 6 * eps);
          }
        }
      }
      EXPECT_LE(worst_p, 1e-9) << m.name << " t=" << t << " " << to_string(mode) << " vs lbs: positions";
      EXPECT_LE(worst_n, 1e-9) << m.name << " t=" << t << " " << to_string(mode) << " vs lbs: normals";
    }
  }
  std::cout << "  " << m.name << ": " << compared << " comparisons of single-influence vertices, joints rigid up to "
            << largest_defect << '\n';
  return compared;
}

TEST(CpuDeform, SingleInfluenceVerticesMoveIdenticallyInAllModes) {
  for (const Model* m : all_rigs()) {
    const size_t compared = expect_single_influence_agreement(*m);
    // Every rig has one-joint vertices, except the one made to have 4 or 8 influences everywhere.
    if (m->name != "eight_influences.gltf") {
      EXPECT_GT(compared, 0u) << m->name;
    }
  }
}

TEST(CpuDeformShared, SingleInfluenceVerticesMoveIdenticallyInAllModes) {
  if (!have_shared()) GTEST_SKIP() << shared_missing_reason();
  for (const Model* m : shared_models()) EXPECT_GT(expect_single_influence_agreement(*m), 0u) << m->name;
}

TEST(CpuDeform, DqsKeepsDistancesWithinAOneJointRegion) {
  for (const char* file : {"bending_arm.gltf", "twisted_cylinder.gltf"}) {
    const Model& m = rig(file);
    const Primitive& prim = only_primitive(m);
    const Clip& clip = m.asset.clips.at(0);
    // Vertices per joint, among those with a single influence.
    std::map<int, std::vector<size_t>> region;
    for (size_t v = 0; v < prim.vertex_count(); ++v)
      if (const int j = single_joint(prim, v); j >= 0) region[j].push_back(v);
    ASSERT_EQ(region.size(), 2u) << file << ": both joints should have a region of their own";
    double worst = 0, largest_motion = 0;
    for (int f = 0; f <= 8; ++f) {
      const Pose pose = sample_pose(m.asset, &clip, clip.last_key * f / 8);
      const DeformedPrimitive out = deform_all(m, pose, BlendMode::kDqs).at(0).at(0);
      for (const auto& [joint, vs] : region) {
        for (size_t a = 0; a < vs.size(); ++a) {
          largest_motion = std::max(largest_motion, glm::length(out.positions[vs[a]] - DVec3(prim.positions[vs[a]])));
          for (size_t b = a + 1; b < vs.size(); ++b) {
            const double before = glm::length(DVec3(prim.positions[vs[a]]) - DVec3(prim.positions[vs[b]]));
            const double after = glm::length(out.positions[vs[a]] - out.positions[vs[b]]);
            worst = std::max(worst, std::abs(after - before) / m.diagonal);
          }
        }
      }
    }
    EXPECT_LE(worst, 1e-9) << file;
    EXPECT_GT(largest_motion, 0.1 * m.diagonal) << file << ": the clip should move a one-joint region";
  }
}

// ---------------------------------------------------------------------------------------------------
// The candy-wrapper case

// Area of the polygon through `ring` (vertices in order), projected on the plane y = const.
double ring_area(const std::vector<DVec3>& positions, const std::vector<size_t>& ring) {
  double twice = 0;
  for (size_t i = 0; i < ring.size(); ++i) {
    const DVec3& a = positions[ring[i]];
    const DVec3& b = positions[ring[(i + 1) % ring.size()]];
    twice += a.z * b.x - a.x * b.z;
  }
  return std::abs(twice) / 2;
}

TEST(CpuDeform, TwistedCylinderKeepsItsCrossSectionUnderDqsAndCollapsesUnderLbs) {
  const Model& m = rig("twisted_cylinder.gltf");
  const Primitive& prim = only_primitive(m);
  const Clip& clip = clip_named(m.asset, "twist");

  // The middle ring: the vertices weighted 50/50, in angular order at rest.
  std::vector<size_t> ring;
  for (size_t v = 0; v < prim.vertex_count(); ++v) {
    const auto in = influences(prim, v);
    if (in.size() == 2 && in[0].second == 0.5 && in[1].second == 0.5) ring.push_back(v);
  }
  ASSERT_EQ(ring.size(), 24u);
  auto angle = [&](size_t v) { return std::atan2(double(prim.positions[v].z), double(prim.positions[v].x)); };
  std::sort(ring.begin(), ring.end(), [&](size_t a, size_t b) { return angle(a) < angle(b); });
  std::vector<DVec3> rest(prim.positions.begin(), prim.positions.end());
  const double rest_area = ring_area(rest, ring);
  ASSERT_GT(rest_area, 0.7);  // a 24-gon of radius 0.5: 0.75

  // At the end of the clip the child joint has turned 180° about y.
  const Pose pose = sample_pose(m.asset, &clip, clip.last_key);
  const Mat4<double> child = joint_matrix(m.asset.skins[0], pose, 1);
  ASSERT_NEAR(child[0][0], -1.0, 1e-6);
  ASSERT_NEAR(child[2][2], -1.0, 1e-6);

  std::map<BlendMode, double> ratio;
  for (BlendMode mode : kModes)
    ratio[mode] = ring_area(deform_all(m, pose, mode).at(0).at(0).positions, ring) / rest_area;
  std::cout << std::fixed << std::setprecision(6) << "  middle-ring area / rest area at 180° twist: lbs "
            << ratio[BlendMode::kLbs] << ", dqs " << ratio[BlendMode::kDqs] << ", dib " << ratio[BlendMode::kDib]
            << '\n'
            << std::defaultfloat;
  for (BlendMode mode : kModes) RecordProperty(std::string("area_ratio_") + to_string(mode), std::to_string(ratio[mode]));
  EXPECT_NEAR(ratio[BlendMode::kDqs], 1.0, 0.02);
  EXPECT_NEAR(ratio[BlendMode::kDib], 1.0, 0.02);
  EXPECT_LT(ratio[BlendMode::kLbs], 0.1);
}

// ---------------------------------------------------------------------------------------------------
// Two-phase skinning of scaled joints

// The sampled value of `node`'s channel on `path` in `clip` at `time`.
std::vector<double> channel_value(const Clip& clip, int node, TargetPath path, double time) {
  for (const Channel& ch : clip.channels)
    if (ch.node == node && ch.path == path) return sample_channel(ch, time);
  return {};
}

// Single-influence vertices of a scaled rig at the end of its clip go exactly where the joint matrix
// (computed here) sends them, in every mode.
void expect_scaled_joint_moves_its_vertices_by_its_matrix(const Model& m, const Pose& pose) {
  const Primitive& prim = only_primitive(m);
  const Skin& skin = m.asset.skins[0];
  ASSERT_TRUE(joint_transforms(skin, pose).any_non_rigid) << m.name;
  size_t on_scaled = 0;
  for (BlendMode mode : kModes) {
    const DeformedPrimitive out = deform_all(m, pose, mode).at(0).at(0);
    for (size_t v = 0; v < prim.vertex_count(); ++v) {
      const int j = single_joint(prim, v);
      if (j < 0) continue;
      on_scaled += j == 1;
      const Mat4<double> mj = joint_matrix(skin, pose, size_t(j));
      const DVec3 expected = apply(mj, DVec3(prim.positions[v]));
      EXPECT_LE(glm::length(out.positions[v] - expected), 1e-9 * m.diagonal)
          << m.name << " " << to_string(mode) << " vertex " << v << ": " << str(out.positions[v]) << " vs "
          << str(expected);
      const DVec3 n = glm::normalize(cofactor(Mat3<double>(mj)) * DVec3(prim.normals[v]));
      EXPECT_LE(glm::length(out.normals[v] - n), 1e-9) << m.name << " " << to_string(mode) << " vertex " << v;
    }
  }
  EXPECT_GT(on_scaled, 0u);
}

TEST(CpuDeformScale, UniformlyScaledJointMovesItsVerticesByItsMatrix) {
  const Model& m = rig("uniform_scale.gltf");
  const Clip& clip = clip_named(m.asset, "grow");
  const Pose pose = sample_pose(m.asset, &clip, clip.last_key);
  const Mat4<double> scaled = joint_matrix(m.asset.skins[0], pose, 1);
  for (int i = 0; i < 3; ++i) ASSERT_EQ(scaled[i][i], 2.0) << "the clip should end at scale 2";
  expect_scaled_joint_moves_its_vertices_by_its_matrix(m, pose);

  // Blended vertices: the rigid parts are both the identity, so v' = (w0 + 2 w1) v + w1 t1 exactly as LBS.
  const Primitive& prim = only_primitive(m);
  const DeformedPrimitive dqs = deform_all(m, pose, BlendMode::kDqs).at(0).at(0);
  const DeformedPrimitive lbs = deform_all(m, pose, BlendMode::kLbs).at(0).at(0);
  size_t blended = 0;
  for (size_t v = 0; v < prim.vertex_count(); ++v) {
    if (influences(prim, v).size() != 2) continue;
    ++blended;
    EXPECT_LE(glm::length(dqs.positions[v] - lbs.positions[v]), 1e-9 * m.diagonal) << "vertex " << v;
  }
  EXPECT_GT(blended, 0u);
}

TEST(CpuDeformScale, NonUniformScaleUsesTwoPhaseBlending) {
  const Model& m = rig("nonuniform_scale.gltf");
  const Clip& clip = clip_named(m.asset, "squash");
  const Skin& skin = m.asset.skins[0];
  const Primitive& prim = only_primitive(m);
  const double t = clip.last_key;
  const Pose pose = sample_pose(m.asset, &clip, t);
  expect_scaled_joint_moves_its_vertices_by_its_matrix(m, pose);

  // docs/DESIGN.md §3.6 by hand: the base joint is the identity; the scaled joint is T(p) R S T(−p), with
  // R and S = diag(s) its sampled rotation and scale, so its rigid part is [R | p − R S p].
  const std::vector<double> s = channel_value(clip, skin.joints[1], TargetPath::kScale, t);
  const std::vector<double> r = channel_value(clip, skin.joints[1], TargetPath::kRotation, t);
  ASSERT_EQ(s.size(), 3u);
  ASSERT_EQ(r.size(), 4u);
  ASSERT_EQ(s[0], 2.0);
  ASSERT_EQ(s[1], 0.5);
  const Quat<double> rotation = glm::normalize(Quat<double>(r[3], r[0], r[1], r[2]));
  const Mat3<double> scale(DVec3(s[0], 0, 0), DVec3(0, s[1], 0), DVec3(0, 0, s[2]));
  const DVec3 p(0, 2, 0);
  const DualQuat<double> q0 = dqskin::identity<double>();
  const DualQuat<double> q1 = dqskin::from_rotation_translation(rotation, p - glm::mat3_cast(rotation) * (scale * p));
  ASSERT_EQ(max_abs(joint_matrix(skin, pose, 0) - Mat4<double>(1.0)), 0.0);
  // The joint matrix agrees with that factorisation.
  const Mat4<double> m1 = joint_matrix(skin, pose, 1);
  const Mat3<double> a1 = glm::mat3_cast(rotation) * scale;
  for (int c = 0; c < 3; ++c) EXPECT_LE(glm::length(DVec3(m1[c]) - a1[c]), 1e-6);

  const DeformedPrimitive dqs = deform_all(m, pose, BlendMode::kDqs).at(0).at(0);
  const DeformedPrimitive dib = deform_all(m, pose, BlendMode::kDib).at(0).at(0);
  const DeformedPrimitive lbs = deform_all(m, pose, BlendMode::kLbs).at(0).at(0);
  size_t blended = 0;
  double dqs_vs_lbs = 0;
  for (size_t v = 0; v < prim.vertex_count(); ++v) {
    const auto in = influences(prim, v);
    if (in.size() != 2) continue;
    ++blended;
    const double w0 = in[0].first == 0 ? in[0].second : in[1].second, w1 = 1 - w0;
    const DVec3 sv = (w0 * Mat3<double>(1.0) + w1 * scale) * DVec3(prim.positions[v]);
    // DLB(w; rigid parts) applied to (Σ w S) v; DIB of two poses is their ScLERP (Kavan et al. §4).
    const DVec3 expected_dqs = dqskin::transform_point(dqskin::normalize(w0 * q0 + w1 * q1), sv);
    const DVec3 expected_dib = dqskin::transform_point(dqskin::sclerp(q0, q1, w1), sv);
    EXPECT_LE(glm::length(dqs.positions[v] - expected_dqs), 1e-9 * m.diagonal)
        << "dqs vertex " << v << ": " << str(dqs.positions[v]) << " vs " << str(expected_dqs);
    EXPECT_LE(glm::length(dib.positions[v] - expected_dib), 1e-9 * m.diagonal)
        << "dib vertex " << v << ": " << str(dib.positions[v]) << " vs " << str(expected_dib);
    dqs_vs_lbs = std::max(dqs_vs_lbs, glm::length(dqs.positions[v] - lbs.positions[v]));
  }
  EXPECT_GT(blended, 0u);
  EXPECT_GT(dqs_vs_lbs, 1e-3) << "the rig should tell two-phase DQS from LBS";
}

// ---------------------------------------------------------------------------------------------------
// Influence sets, morph targets, several skins

TEST(CpuDeform, EightInfluencesAreAllUsed) {
  const Model& m = rig("eight_influences.gltf");
  const Primitive& prim = only_primitive(m);
  const Skin& skin = m.asset.skins[0];
  ASSERT_EQ(prim.influences, 8);
  ASSERT_EQ(skin.joints.size(), 8u);
  size_t eight = 0;
  for (size_t v = 0; v < prim.vertex_count(); ++v) eight += influences(prim, v).size() == 8;
  EXPECT_GT(eight, 0u);

  const Clip& clip = clip_named(m.asset, "wave");
  const Pose pose = sample_pose(m.asset, &clip, 0.3);
  // Move only the 8th joint (a leaf): turn it 40° about z and lift it.
  Pose moved = pose;
  Mat4<double>& world = moved.world[size_t(skin.joints[7])];
  world = glm::rotate(glm::translate(world, DVec3(0, 0.3, 0.1)), 40.0 * std::numbers::pi / 180, DVec3(0, 0, 1));

  for (BlendMode mode : kModes) {
    const DeformedPrimitive before = deform_all(m, pose, mode).at(0).at(0);
    const DeformedPrimitive after = deform_all(m, moved, mode).at(0).at(0);
    size_t moved_count = 0, still = 0;
    for (size_t v = 0; v < prim.vertex_count(); ++v) {
      bool on_joint7 = false;
      for (const auto& [j, w] : influences(prim, v)) on_joint7 = on_joint7 || j == 7;
      const double d = glm::length(after.positions[v] - before.positions[v]);
      if (on_joint7) {
        ++moved_count;
        EXPECT_GT(d, 1e-4) << to_string(mode) << " vertex " << v << " has weight on joint 7 but did not move";
      } else {
        ++still;
        EXPECT_EQ(d, 0.0) << to_string(mode) << " vertex " << v << " has no weight on joint 7 but moved";
      }
    }
    EXPECT_GT(moved_count, 0u);
    EXPECT_GT(still, 0u);
  }
}

TEST(CpuDeform, MorphTargetsApplyBeforeSkinning) {
  const Model& m = rig("morph_skin.gltf");
  const Primitive& prim = only_primitive(m);
  const int node = m.skinned.at(0).node;
  ASSERT_EQ(prim.targets.size(), 2u);

  // Rest pose: the mesh's default weights [0.5, 0], identity joint matrices.
  const Pose rest = sample_pose(m.asset, nullptr, 0);
  ASSERT_EQ(rest.weights[size_t(node)], (std::vector<double>{0.5, 0.0}));
  for (BlendMode mode : kModes) {
    const DeformedPrimitive out = deform_all(m, rest, mode).at(0).at(0);
    for (size_t v = 0; v < prim.vertex_count(); ++v) {
      const DVec3 expected = DVec3(prim.positions[v]) + 0.5 * DVec3(prim.targets[0].positions[v]);
      EXPECT_LE(glm::length(out.positions[v] - expected), 1e-9 * m.diagonal) << to_string(mode) << " vertex " << v;
      const DVec3 n = glm::normalize(DVec3(prim.normals[v]) + 0.5 * DVec3(prim.targets[0].normals[v]));
      EXPECT_LE(glm::length(out.normals[v] - n), 1e-9) << to_string(mode) << " vertex " << v;
    }
  }

  // End of the clip: weights [0.25, 1], the child joint turned 60° about x.
  const Clip& clip = clip_named(m.asset, "morph");
  const Pose pose = sample_pose(m.asset, &clip, clip.last_key);
  const std::vector<double>& w = pose.weights[size_t(node)];
  ASSERT_EQ(w, (std::vector<double>{0.25, 1.0}));
  const Skin& skin = m.asset.skins[0];
  double skin_then_morph = 0;  // how far the wrong order would be off
  for (BlendMode mode : kModes) {
    const DeformedPrimitive out = deform_all(m, pose, mode).at(0).at(0);
    for (size_t v = 0; v < prim.vertex_count(); ++v) {
      const auto in = influences(prim, v);
      Mat4<double> blended(0.0);
      for (const auto& [j, wj] : in) blended += wj * joint_matrix(skin, pose, j);
      const DVec3 expected = apply(blended, morphed_position(prim, w, v));
      if (mode == BlendMode::kLbs || in.size() == 1) {
        EXPECT_LE(glm::length(out.positions[v] - expected), 1e-9 * m.diagonal)
            << to_string(mode) << " vertex " << v << ": " << str(out.positions[v]) << " vs " << str(expected);
        const DVec3 n = glm::normalize(cofactor(Mat3<double>(blended)) * morphed_normal(prim, w, v));
        EXPECT_LE(glm::length(out.normals[v] - n), 1e-9) << to_string(mode) << " vertex " << v;
      }
      const DVec3 wrong = apply(blended, DVec3(prim.positions[v])) + (morphed_position(prim, w, v) - DVec3(prim.positions[v]));
      skin_then_morph = std::max(skin_then_morph, glm::length(wrong - expected));
    }
  }
  EXPECT_GT(skin_then_morph, 1e-2) << "the rig should tell morph-then-skin from skin-then-morph";
}

TEST(CpuDeform, TwoSkinsDeformIndependently) {
  const Model& m = rig("two_skins.gltf");
  ASSERT_EQ(m.skinned.size(), 2u);
  ASSERT_NE(m.skinned[0].skin, m.skinned[1].skin);
  const Clip& clip = clip_named(m.asset, "sway");
  const std::vector<MeshInstance> instances = mesh_instances(m.asset, choose_scene(m.asset, -1));
  for (double t : some_times(clip)) {
    const Pose pose = sample_pose(m.asset, &clip, t);
    for (BlendMode mode : kModes) {
      const DeformedFrame frame = deform_frame(m.asset, instances, pose, mode);
      ASSERT_EQ(frame.primitives.size(), 2u);
      for (size_t i = 0; i < 2; ++i) {
        const MeshInstance& inst = m.skinned[i];
        const Skin& skin = m.asset.skins[size_t(inst.skin)];
        const Primitive& prim = m.asset.meshes[size_t(inst.mesh)].primitives[0];
        for (size_t v = 0; v < prim.vertex_count(); ++v) {
          const auto in = influences(prim, v);
          if (mode != BlendMode::kLbs && in.size() != 1) continue;
          Mat4<double> blended(0.0);
          for (const auto& [j, wj] : in) blended += wj * joint_matrix(skin, pose, j);
          const DVec3 expected = apply(blended, DVec3(prim.positions[v]));
          EXPECT_LE(glm::length(frame.primitives[i].positions[v] - expected), 1e-9 * m.diagonal)
              << "t=" << t << " " << to_string(mode) << " instance " << i << " vertex " << v;
        }
      }
    }
  }

  // Moving a joint of skin B changes instance B only.
  const Pose pose = sample_pose(m.asset, &clip, 0.5);
  Pose moved = pose;
  const Skin& skin_b = m.asset.skins[size_t(m.skinned[1].skin)];
  for (int joint : skin_b.joints)
    moved.world[size_t(joint)] = glm::translate(Mat4<double>(1.0), DVec3(0, 0, 1)) * moved.world[size_t(joint)];
  const DeformedFrame a = deform_frame(m.asset, instances, pose, BlendMode::kDqs);
  const DeformedFrame b = deform_frame(m.asset, instances, moved, BlendMode::kDqs);
  ASSERT_EQ(b.primitives.size(), 2u);
  EXPECT_EQ(a.primitives[0].positions, b.primitives[0].positions);
  EXPECT_EQ(a.primitives[0].normals, b.primitives[0].normals);
  for (size_t v = 0; v < a.primitives[1].positions.size(); ++v)
    EXPECT_NEAR(b.primitives[1].positions[v].z - a.primitives[1].positions[v].z, 1.0, 1e-9) << "vertex " << v;
}

// ---------------------------------------------------------------------------------------------------
// Threads

bool bit_identical(const DeformedPrimitive& a, const DeformedPrimitive& b) {
  auto same = [](const auto& x, const auto& y) {
    return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof x[0]) == 0);
  };
  return same(a.positions, b.positions) && same(a.normals, b.normals) && same(a.tangents, b.tangents);
}

void expect_thread_count_does_not_matter(const Asset& asset, const MeshInstance& inst, const Pose& pose,
                                         const std::string& what) {
  const JointTransforms jt = joint_transforms(asset.skins[size_t(inst.skin)], pose);
  for (BlendMode mode : kModes) {
    const DeformedPrimitive one = deform_primitive(asset, inst, 0, pose, &jt, mode, 1);
    for (int threads : {2, 3, 8}) {
      const DeformedPrimitive many = deform_primitive(asset, inst, 0, pose, &jt, mode, threads);
      EXPECT_TRUE(bit_identical(one, many)) << what << " " << to_string(mode) << " with " << threads << " threads";
    }
  }
}

// A copy of m's first skinned primitive repeated until it has at least `vertices` vertices (each copy
// shifted a little along x), so that the deformer really splits it: it gives each thread at least 2048
// vertices. Returns the asset; the primitive is the one m.skinned[0] draws.
Asset tiled(const Model& m, size_t vertices) {
  Asset big = m.asset;
  Primitive& prim = big.meshes[size_t(m.skinned.at(0).mesh)].primitives.at(0);
  const Primitive one = prim;
  for (int copy = 1; prim.vertex_count() < vertices; ++copy) {
    for (size_t v = 0; v < one.vertex_count(); ++v) {
      prim.positions.push_back(one.positions[v] + glm::vec3(0.001f * float(copy), 0, 0));
      if (!one.normals.empty()) prim.normals.push_back(one.normals[v]);
      if (!one.tangents.empty()) prim.tangents.push_back(one.tangents[v]);
      for (size_t k = 0; k < prim.targets.size(); ++k) {
        MorphTarget& t = prim.targets[k];
        if (!t.positions.empty()) t.positions.push_back(one.targets[k].positions[v]);
        if (!t.normals.empty()) t.normals.push_back(one.targets[k].normals[v]);
        if (!t.tangents.empty()) t.tangents.push_back(one.targets[k].tangents[v]);
      }
    }
    prim.joints.insert(prim.joints.end(), one.joints.begin(), one.joints.end());
    prim.weights.insert(prim.weights.end(), one.weights.begin(), one.weights.end());
    if (!one.uv0.empty()) prim.uv0.insert(prim.uv0.end(), one.uv0.begin(), one.uv0.end());
  }
  prim.indices.clear();
  return big;
}

TEST(CpuDeform, ResultsDoNotDependOnTheThreadCount) {
  const Model& m = rig("twisted_cylinder.gltf");  // the largest rig, 792 vertices: tiled to 6336+
  const Asset big = tiled(m, 3 * 2048);
  const Clip& clip = clip_named(big, "twist");
  expect_thread_count_does_not_matter(big, m.skinned[0], sample_pose(big, &clip, 0.6), "tiled twisted_cylinder");
}

TEST(CpuDeformShared, ResultsDoNotDependOnTheThreadCount) {
  if (!have_shared()) GTEST_SKIP() << shared_missing_reason();
  const Model& cesium = *shared_models().at(1);  // 3273 vertices: tiled twice
  ASSERT_EQ(cesium.name, "CesiumMan/CesiumMan.glb");
  const Asset big = tiled(cesium, 3 * 2048);
  expect_thread_count_does_not_matter(big, cesium.skinned.at(0), sample_pose(big, &big.clips.at(0), 1.0), cesium.name);
}

// ---------------------------------------------------------------------------------------------------
// Weights that the deformer corrects, on an Asset built in memory

// Two joints: "root" at the origin and "tip" at (1, 0, 0), turned 90° about z at rest; the bind pose has
// the tip unturned (inverse bind = translation by −1 along x). One unindexed primitive of
// `weights.size() / 2` vertices, all at (1.5, 0, 0) with normal +z, weights (root, tip) as given.
Asset two_joint_asset(const std::vector<float>& weights) {
  Asset a;
  a.path = "(in memory)";
  a.nodes.resize(3);
  a.nodes[0].name = "mesh";
  a.nodes[0].mesh = 0;
  a.nodes[0].skin = 0;
  a.nodes[1].name = "root";
  a.nodes[1].children = {2};
  a.nodes[2].name = "tip";
  a.nodes[2].parent = 1;
  a.nodes[2].local.translation = DVec3(1, 0, 0);
  a.nodes[2].local.rotation = glm::angleAxis(std::numbers::pi / 2, DVec3(0, 0, 1));

  Skin skin;
  skin.name = "skin";
  skin.joints = {1, 2};
  skin.inverse_bind = {Mat4<double>(1.0), glm::translate(Mat4<double>(1.0), DVec3(-1, 0, 0))};
  a.skins.push_back(skin);

  Primitive p;
  const size_t n = weights.size() / 2;
  p.positions.assign(n, glm::vec3(1.5f, 0, 0));
  p.normals.assign(n, glm::vec3(0, 0, 1));
  p.influences = 4;
  for (size_t v = 0; v < n; ++v) {
    p.joints.insert(p.joints.end(), {0, 1, 0, 0});
    p.weights.insert(p.weights.end(), {weights[2 * v], weights[2 * v + 1], 0.0f, 0.0f});
  }
  Mesh mesh;
  mesh.name = "mesh";
  mesh.primitives.push_back(p);
  a.meshes.push_back(mesh);
  a.scenes.push_back({"scene", {0, 1}});
  a.default_scene = 0;
  return a;
}

bool mentions(const std::vector<std::string>& messages, const std::string& text) {
  return std::any_of(messages.begin(), messages.end(), [&](const std::string& m) { return m.find(text) != std::string::npos; });
}

TEST(CpuDeformWeights, WeightsThatDoNotSumToOneAreRenormalized) {
  // Vertex 0 sums to 1; 1 to 0.5; 2 to 2. All three must land where vertex 0 does.
  const Asset a = two_joint_asset({0.5f, 0.5f, 0.25f, 0.25f, 1.0f, 1.0f});
  const Pose pose = sample_pose(a, nullptr, 0);
  const std::vector<MeshInstance> inst = mesh_instances(a, choose_scene(a, -1));
  ASSERT_EQ(inst.size(), 1u);
  // LBS by hand: ½ (I + M_tip) p, with M_tip = R_z(90°) about (1, 0, 0): (1.5, 0, 0) ↦ (1, 0.5, 0).
  const DVec3 lbs_expected = 0.5 * DVec3(1.5, 0, 0) + 0.5 * DVec3(1, 0.5, 0);
  for (BlendMode mode : kModes) {
    const DeformedFrame f = deform_frame(a, inst, pose, mode);
    const std::vector<DVec3>& p = f.primitives.at(0).positions;
    EXPECT_LE(glm::length(p[1] - p[0]), 1e-12) << to_string(mode);
    EXPECT_LE(glm::length(p[2] - p[0]), 1e-12) << to_string(mode);
    EXPECT_GT(glm::length(p[0] - DVec3(1.5, 0, 0)), 0.1) << to_string(mode) << ": the blend should move the vertex";
    if (mode == BlendMode::kLbs) {
      EXPECT_LE(glm::length(p[0] - lbs_expected), 1e-12) << str(p[0]);
    }
  }
  const std::vector<std::string> warnings = weight_warnings(a);
  EXPECT_TRUE(mentions(warnings, "2 vertices have weights that do not sum to 1")) << ::testing::PrintToString(warnings);
  EXPECT_FALSE(mentions(warnings, "no weight")) << ::testing::PrintToString(warnings);
}

TEST(CpuDeformWeights, ZeroWeightVertexStaysInBindPose) {
  const Asset a = two_joint_asset({0.0f, 0.0f, 0.0f, 1.0f});
  const Pose pose = sample_pose(a, nullptr, 0);
  const std::vector<MeshInstance> inst = mesh_instances(a, choose_scene(a, -1));
  for (BlendMode mode : kModes) {
    const DeformedPrimitive p = deform_frame(a, inst, pose, mode).primitives.at(0);
    EXPECT_EQ(p.positions[0], DVec3(1.5, 0, 0)) << to_string(mode);
    EXPECT_EQ(p.normals[0], DVec3(0, 0, 1)) << to_string(mode);
    // The other vertex follows the tip: turned 90° about (1, 0, 0).
    EXPECT_LE(glm::length(p.positions[1] - DVec3(1, 0.5, 0)), 1e-12) << to_string(mode) << " " << str(p.positions[1]);
    EXPECT_LE(glm::length(p.normals[1] - DVec3(0, 0, 1)), 1e-12) << to_string(mode);
  }
  const std::vector<std::string> warnings = weight_warnings(a);
  EXPECT_TRUE(mentions(warnings, "1 vertices have no weight; they stay in the bind pose"))
      << ::testing::PrintToString(warnings);
  EXPECT_FALSE(mentions(warnings, "do not sum to 1")) << ::testing::PrintToString(warnings);
}

}  // namespace
}  // namespace dqskin
