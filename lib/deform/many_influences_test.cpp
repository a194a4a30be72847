// More than 8 influences per vertex (scripts/testdata/make_influence_cases.py: 12 in JOINTS_0..2, 20 in
// JOINTS_0..4): every deformer (the CPU reference, the fast CPU deformer, the GPU path on each headless
// backend), lbs and dqs, against an independent double-precision computation written here from the
// definitions: joint matrix world(joint) · inverseBind(joint) (glTF 2.0 §3.7.3.3), LBS Σ wᵢ Mᵢ p, DQS as
// DLB of the rigid parts with each influence flipped to the heaviest's hemisphere [Kavan et al. 2008 §4].
// It shares only sample_pose (node world matrices) with the code under test.
//
// Tolerances, as shares of the animation's bounding-box diagonal: 1e-9 for the CPU reference (double
// against double; only the order of the sums differs), 1e-5 for the float paths (test_support/
// deform_accuracy.hpp: float keeps 6e-8 relative, the rest is the float palette and up to 20 rounded
// terms). Dropping the small weights moves the surface by more than 1e-2 of the diagonal
// (SmallWeightsMoveTheSurface), so a deformer that read fewer sets would fail by three orders of
// magnitude. The reference is held to it on its own double result (deform_frame); through the Deformer
// interface every path hands out float batches.
#include "dqskin/deformer.hpp"
#include "dqskin/load.hpp"
#include "../test_support/deform_accuracy.hpp"
#include "../test_support/gpu_context.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <limits>
#include <numeric>

namespace dqskin {
namespace {

namespace fs = std::filesystem;

std::string influence_case(const std::string& name) { return std::string(DQSKIN_INFLUENCE_CASES_DIR) + "/" + name; }

// Vertex v's influences with weight, divided by their sum, in slot order; only the `keep` largest (ties to
// the earlier slot) when keep is given.
std::vector<std::pair<int, double>> influences_of(const Primitive& prim, size_t v,
                                                  size_t keep = std::numeric_limits<size_t>::max()) {
  std::vector<std::pair<int, double>> in;
  const size_t per = size_t(prim.influences);
  for (size_t k = 0; k < per; ++k)
    if (prim.weights[v * per + k] > 0) in.push_back({prim.joints[v * per + k], double(prim.weights[v * per + k])});
  if (in.size() > keep) {
    std::stable_sort(in.begin(), in.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    in.resize(keep);
  }
  double sum = 0;
  for (const auto& i : in) sum += i.second;
  for (auto& i : in) i.second /= sum;
  return in;
}

// The rigs' one skinned primitive at `pose`, from the definitions (see the file comment). The rigs' joints
// are rigid (rotations and translations), which the DQS branch checks.
std::vector<glm::dvec3> expected_positions(const Asset& asset, const Pose& pose, BlendMode mode,
                                           size_t keep = std::numeric_limits<size_t>::max()) {
  const Skin& skin = asset.skins.at(0);
  const Primitive& prim = asset.meshes.at(0).primitives.at(0);
  std::vector<glm::dmat4> joint(skin.joints.size());
  std::vector<glm::dquat> real(skin.joints.size()), dual(skin.joints.size());
  for (size_t j = 0; j < joint.size(); ++j) {
    joint[j] = pose.world[size_t(skin.joints[j])] * skin.inverse_bind[j];
    const glm::dmat3 r(joint[j]);
    EXPECT_NEAR(glm::determinant(r), 1.0, 1e-9) << "joint " << j << " is not rigid";
    real[j] = glm::quat_cast(r);
    const glm::dvec3 t(joint[j][3]);
    dual[j] = 0.5 * (glm::dquat(0.0, t.x, t.y, t.z) * real[j]);  // d = ½ t r
  }
  std::vector<glm::dvec3> out(prim.vertex_count());
  for (size_t v = 0; v < out.size(); ++v) {
    const glm::dvec3 p(prim.positions[v]);
    const auto in = influences_of(prim, v, keep);
    if (mode == BlendMode::kLbs) {
      glm::dmat4 m(0.0);
      for (const auto& [j, w] : in) m += w * joint[size_t(j)];
      out[v] = glm::dvec3(m * glm::dvec4(p, 1.0));
      continue;
    }
    // The heaviest influence (the first of equals) is the pivot.
    const auto pivot = std::max_element(in.begin(), in.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
    const glm::dquat& pr = real[size_t(pivot->first)];
    glm::dquat r(0, 0, 0, 0), d(0, 0, 0, 0);
    for (const auto& [j, w] : in) {
      const double s = glm::dot(real[size_t(j)], pr) < 0 ? -w : w;
      r = r + s * real[size_t(j)];
      d = d + s * dual[size_t(j)];
    }
    const double length = glm::length(r);
    r = r / length;
    d = d / length;
    const glm::dquat t = 2.0 * (d * glm::conjugate(r));  // translation t = 2 d r*
    out[v] = r * p + glm::dvec3(t.x, t.y, t.z);
  }
  return out;
}

struct Case {
  std::string file;
  BlendMode mode;
  Backend backend;
};

class ManyInfluences : public testing::TestWithParam<Case> {};

TEST_P(ManyInfluences, DeformerMatchesTheDefinitionOnEveryFrame) {
  const Case& c = GetParam();
  const std::string path = influence_case(c.file);
  ASSERT_TRUE(fs::exists(path)) << path << " was not generated (scripts/testdata/make_influence_cases.py)";
  std::unique_ptr<GpuContext> context;
  if (c.backend == Backend::kEgl || c.backend == Backend::kOsMesa) {
    context = testing_support::context_or_null(c.backend);
    if (!context) GTEST_SKIP() << "no OpenGL 4.3 context with backend " << to_string(c.backend);
  }
  const Asset asset = load_asset(path);
  ASSERT_GE(asset.meshes.at(0).primitives.at(0).influences, 12);
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  ASSERT_EQ(instances.size(), 1u);
  const Clip* clip = &asset.clips.at(0);
  const std::vector<double> times = testing_support::accuracy_times(clip);
  double worst = 0;
  glm::dvec3 lo(1e300), hi(-1e300);
  size_t frames = 0;
  if (c.backend == Backend::kCpu) {
    // The reference's own double-precision result (its Deformer hands out float batches).
    for (double t : times) {
      const Pose pose = sample_pose(asset, clip, t);
      const DeformedFrame got = deform_frame(asset, instances, pose, c.mode);
      const std::vector<glm::dvec3> want = expected_positions(asset, pose, c.mode);
      ASSERT_EQ(got.primitives.size(), 1u);
      ASSERT_EQ(got.primitives[0].positions.size(), want.size());
      for (size_t v = 0; v < want.size(); ++v) {
        worst = std::max(worst, glm::distance(got.primitives[0].positions[v], want[v]));
        lo = glm::min(lo, want[v]);
        hi = glm::max(hi, want[v]);
      }
      ++frames;
    }
  }
  DeformerOptions options;
  options.mode = c.mode;
  options.backend = c.backend;
  std::unique_ptr<Deformer> deformer =
      c.backend == Backend::kCpu ? nullptr : make_deformer(context.get(), asset, instances, options);
  if (deformer) {
    deformer->run(clip, times, [&](const DeformedBatch& batch) {
      ASSERT_EQ(batch.primitives.size(), 1u);
      const DeformedBatch::Primitive& got = batch.primitives[0];
      for (size_t f = 0; f < batch.frame_count; ++f, ++frames) {
        const std::vector<glm::dvec3> want =
            expected_positions(asset, sample_pose(asset, clip, times[batch.first_frame + f]), c.mode);
        ASSERT_EQ(got.vertices, want.size());
        for (size_t v = 0; v < want.size(); ++v) {
          const size_t o = (f * got.vertices + v) * 3;
          worst = std::max(worst, glm::distance(glm::dvec3(got.positions[o], got.positions[o + 1], got.positions[o + 2]), want[v]));
          lo = glm::min(lo, want[v]);
          hi = glm::max(hi, want[v]);
        }
      }
    });
  }
  ASSERT_EQ(frames, times.size());
  const double share = c.backend == Backend::kCpu ? 1e-9 : 1e-5;
  const double tolerance = share * glm::distance(lo, hi);
  std::cout << "  " << c.file << " " << to_string(c.mode) << " " << to_string(c.backend) << ": max position error "
            << worst << " (tolerance " << tolerance << ", " << share << " of the diagonal)\n";
  EXPECT_LE(worst, tolerance);
}

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const char* file : {"twelve_influences.gltf", "twenty_influences.gltf"})
    for (BlendMode mode : {BlendMode::kLbs, BlendMode::kDqs})
      for (Backend backend : {Backend::kCpu, Backend::kFastCpu, Backend::kEgl, Backend::kOsMesa})
        out.push_back({file, mode, backend});
  return out;
}

INSTANTIATE_TEST_SUITE_P(All, ManyInfluences, testing::ValuesIn(cases()), [](const testing::TestParamInfo<Case>& p) {
  std::string name = fs::path(p.param.file).stem().string() + "_" + to_string(p.param.mode) + "_" + to_string(p.param.backend);
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
});

// The rigs are made so that every influence counts: with only the 4 largest of the 20, the definition's
// surface is more than 1e-2 of the diagonal away at some frame, in both modes.
TEST(ManyInfluences, SmallWeightsMoveTheSurface) {
  const Asset asset = load_asset(influence_case("twenty_influences.gltf"));
  const Clip* clip = &asset.clips.at(0);
  for (BlendMode mode : {BlendMode::kLbs, BlendMode::kDqs}) {
    double moved = 0;
    glm::dvec3 lo(1e300), hi(-1e300);
    for (double t : testing_support::accuracy_times(clip)) {
      const Pose pose = sample_pose(asset, clip, t);
      const std::vector<glm::dvec3> all = expected_positions(asset, pose, mode), top = expected_positions(asset, pose, mode, 4);
      for (size_t v = 0; v < all.size(); ++v) {
        moved = std::max(moved, glm::distance(all[v], top[v]));
        lo = glm::min(lo, all[v]);
        hi = glm::max(hi, all[v]);
      }
    }
    EXPECT_GT(moved, 1e-2 * glm::distance(lo, hi)) << to_string(mode);
  }
}

// DQS's hemisphere rule is exercised per influence: at some frame some vertex has an influence whose
// rotation is on the other side of the heaviest's (dot < 0), so the test above covers the flip.
TEST(ManyInfluences, SomeInfluencesAreAntipodalToTheHeaviest) {
  const Asset asset = load_asset(influence_case("twenty_influences.gltf"));
  const Clip* clip = &asset.clips.at(0);
  const Skin& skin = asset.skins.at(0);
  const Primitive& prim = asset.meshes.at(0).primitives.at(0);
  size_t antipodal = 0;
  for (double t : testing_support::accuracy_times(clip)) {
    const Pose pose = sample_pose(asset, clip, t);
    for (size_t v = 0; v < prim.vertex_count(); ++v) {
      const auto in = influences_of(prim, v);
      const auto pivot = std::max_element(in.begin(), in.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
      // w ≥ 0, as every deformer's palette holds it (from_rigid_matrix).
      auto rotation = [&](int j) {
        const glm::dquat q =
            glm::quat_cast(glm::dmat3(pose.world[size_t(skin.joints[size_t(j)])] * skin.inverse_bind[size_t(j)]));
        return q.w < 0 ? -q : q;
      };
      const glm::dquat pr = rotation(pivot->first);
      for (const auto& [j, w] : in)
        if (glm::dot(rotation(j), pr) < 0) ++antipodal;
    }
  }
  std::cout << "  influences antipodal to their vertex's heaviest, over all frames: " << antipodal << "\n";
  EXPECT_GT(antipodal, 0u);
}

}  // namespace
}  // namespace dqskin
