// Sockets and root motion (docs/DESIGN.md §3.11): a prop placed by the socket transforms lands where the
// bake put it, the dual quaternions agree with the matrices, the texture holds the JSON's values, and an
// in-place bake moved back by its root motion track gives the normal bake.
#include "dqskin/animation.hpp"
#include "dqskin/bake.hpp"
#include "dqskin/dual_quat.hpp"
#include "dqskin/load.hpp"
#include "dqskin/skinning.hpp"
#include "../texture/texel_image.hpp"
#include "../test_support/ply_test_reader.hpp"
#include "../test_support/read_file.hpp"
#include "../test_support/scratch_dir.hpp"
#include "../test_support/test_models.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using testing_support::model_path;
using testing_support::ScratchDir;
using Json = nlohmann::json;

BakeReport bake_one(const fs::path& input, const fs::path& out, const MotionOptions& motion, double fps = 30,
                    Backend backend = Backend::kFastCpu) {
  BakeOptions o;
  o.plan.out_dir = out.string();
  o.plan.frames.fps = fps;
  o.formats = unsigned(BakeFormat::kPly);
  o.backend = backend;
  o.jobs = 2;
  o.motion = motion;
  BakeReport r = bake({input.string()}, o);
  EXPECT_FALSE(r.any_failed()) << (r.inputs.empty() ? "" : r.inputs[0].error);
  return r;
}

Json read_json(const fs::path& path) { return Json::parse(testing_support::read_file(path)); }

Mat4<double> matrix_of(const Json& column_major) {
  Mat4<double> m(1.0);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) m[c][r] = column_major[size_t(4 * c + r)].get<double>();
  return m;
}

Vec3<double> vertex(const PlyFile& ply, size_t v) {
  const size_t stride = ply.vertex_properties.size();
  return {ply.vertex_data[v * stride], ply.vertex_data[v * stride + 1], ply.vertex_data[v * stride + 2]};
}

size_t vertex_count(const PlyFile& ply) { return ply.vertex_data.size() / ply.vertex_properties.size(); }

// The folder of the only clip of a one-clip bake, or of `clip`.
fs::path clip_folder(const fs::path& out, const std::string& stem, const std::string& clip = "") {
  if (!clip.empty()) return out / stem / clip;
  for (const auto& entry : fs::directory_iterator(out / stem)) return entry.path();
  return {};
}

std::vector<fs::path> frame_files(const fs::path& folder) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().extension() == ".ply") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

// The prop of socket_prop.gltf is a rigid child of "hand": at every frame its baked vertices are the socket
// matrix times its node's local matrix times its rest vertices. Tolerance 2e-6 scene units: the PLY holds
// float32 positions of magnitude up to 8 (ulp 4.8e-7), computed in float by the fast CPU deformer from the
// float joint matrix; a wrong frame, node or matrix order is off by 0.01 or more.
TEST(Sockets, PlaceTheRigidPropAtEveryFrame) {
  const ScratchDir scratch("sockets_prop");
  const fs::path input = model_path("socket_prop.gltf");
  bake_one(input, scratch.path(), {{"hand", "#3"}, false, ""});
  const fs::path folder = clip_folder(scratch.path(), "socket_prop", "walk");
  const Json doc = read_json(folder / "sockets.json");
  EXPECT_EQ(doc["format"], "dqskin sockets");
  ASSERT_EQ(doc["sockets"].size(), 2u);
  EXPECT_EQ(doc["sockets"][0]["name"], "hand");
  EXPECT_EQ(doc["sockets"][0]["node"], 2);
  EXPECT_EQ(doc["sockets"][1]["name"], "sword");
  EXPECT_FALSE(doc["in_place"].get<bool>());

  const Asset asset = load_asset(input.string());
  const Mat4<double> prop_local = asset.nodes[3].local.to_matrix();
  const std::vector<glm::vec3>& rest = asset.meshes[size_t(asset.nodes[3].mesh)].primitives[0].positions;
  const std::vector<fs::path> frames = frame_files(folder);
  ASSERT_EQ(frames.size(), doc["frame_count"].get<size_t>());
  ASSERT_EQ(frames.size(), 61u);
  double worst = 0, worst_dq = 0, worst_sword = 0;
  for (size_t f = 0; f < frames.size(); ++f) {
    const PlyFile ply = read_ply(frames[f]);
    ASSERT_EQ(vertex_count(ply), 272u + rest.size());
    const Mat4<double> hand = matrix_of(doc["sockets"][0]["matrices"][f]);
    const Mat4<double> sword = matrix_of(doc["sockets"][1]["matrices"][f]);
    const Json& q = doc["sockets"][0]["dual_quaternions"][f];
    auto at = [&](size_t i) { return q[i].get<double>(); };
    const DualQuat<double> dq(Quat<double>(at(3), at(0), at(1), at(2)), Quat<double>(at(7), at(4), at(5), at(6)));
    for (size_t v = 0; v < rest.size(); ++v) {
      const Vec3<double> local = Vec3<double>(prop_local * glm::dvec4(glm::dvec3(rest[v]), 1.0));
      const Vec3<double> placed = Vec3<double>(hand * glm::dvec4(local, 1.0));
      worst = std::max(worst, glm::length(placed - vertex(ply, 272 + v)));
      worst_dq = std::max(worst_dq, glm::length(transform_point(dq, local) - placed));
      worst_sword = std::max(worst_sword, glm::length(Vec3<double>(sword * glm::dvec4(glm::dvec3(rest[v]), 1.0)) - placed));
    }
  }
  std::printf("socket_prop: prop from the socket vs baked, largest distance %.3g; dual quaternion vs matrix %.3g; "
              "sword node vs hand × local %.3g\n", worst, worst_dq, worst_sword);
  EXPECT_LT(worst, 2e-6);
  EXPECT_LT(worst_dq, 1e-12);    // both double: the same rigid motion
  EXPECT_LT(worst_sword, 1e-12);

  // The texture: texel (5 s + k, f) is the JSON's value rounded to float, exactly.
  const Json& tex = doc["texture"];
  ASSERT_EQ(tex["width"], 10);
  ASSERT_EQ(tex["height"], 61);
  texture::TexelFileReader reader((folder / "sockets.exr").string(), "sockets.exr", texture::TexelType::kFloat32, 10, 61, 4);
  texture::TexelImage rows;
  reader.read(0, 61, rows);
  size_t mismatches = 0;
  for (size_t s = 0; s < 2; ++s)
    for (size_t f = 0; f < 61; ++f) {
      const Json& m = doc["sockets"][s]["matrices"][f];
      const Json& q = doc["sockets"][s]["dual_quaternions"][f];
      for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 3; ++r) mismatches += rows.get(5 * s + size_t(r), f, c) != float(m[size_t(4 * c + r)].get<double>());
        mismatches += rows.get(5 * s + 3, f, c) != float(q[size_t(c)].get<double>());
        mismatches += rows.get(5 * s + 4, f, c) != float(q[size_t(4 + c)].get<double>());
      }
    }
  EXPECT_EQ(mismatches, 0u);
}

TEST(Sockets, FilesAreDeterministicAndInTheManifest) {
  const ScratchDir a("sockets_a"), b("sockets_b");
  const BakeReport ra = bake_one(model_path("socket_prop.gltf"), a.path(), {{"hand"}, true, ""});
  bake_one(model_path("socket_prop.gltf"), b.path(), {{"hand"}, true, ""});
  for (const char* name : {"sockets.json", "sockets.exr", "root_motion.json"}) {
    const fs::path relative = fs::path("socket_prop/walk") / name;
    EXPECT_EQ(testing_support::read_file(a.path() / relative), testing_support::read_file(b.path() / relative)) << name;
    EXPECT_TRUE(std::any_of(ra.outputs.begin(), ra.outputs.end(), [&](const BakeOutput& o) { return o.path == relative.string(); }))
        << name << " is not among the bake's outputs";
  }
}

// An in-place bake and its track give back the normal bake: every vertex v of frame f of the normal bake is
// M(t_f) · v' with v' the in-place bake's. Tolerance: 1e-5 of the scene's size (the largest distance of a
// baked vertex from the origin): both bakes are float32 positions computed in float, from joint matrices
// that differ by a rigid motion before rounding to float, so they round differently by a few ulps; a
// wrong sign of yaw or x moves vertices by the size of the motion. The in-place root, recorded as a socket,
// stays on the ground's origin with no heading.
struct WalkResult {
  double worst = 0, scene = 0, travelled = 0, turned = 0, root_drift = 0, root_yaw = 0;
};

WalkResult compare_in_place(const fs::path& input, const std::string& clip, double fps, const std::string& root_joint = "") {
  const ScratchDir normal("root_normal"), in_place("root_in_place");
  bake_one(input, normal.path(), {{}, false, ""}, fps);
  const std::string stem = input.stem().string();
  WalkResult out;
  // The chosen root, recorded as a socket of the in-place bake.
  const Json first = [&] {
    bake_one(input, in_place.path(), {{}, true, root_joint}, fps);
    return read_json(clip_folder(in_place.path(), stem, clip) / "root_motion.json");
  }();
  const std::string root = "#" + std::to_string(first["root"]["node"].get<int>());
  fs::remove_all(in_place.path() / stem);
  bake_one(input, in_place.path(), {{root}, true, root_joint}, fps);
  const fs::path a = clip_folder(normal.path(), stem, clip), b = clip_folder(in_place.path(), stem, clip);
  const Json track = read_json(b / "root_motion.json");
  EXPECT_EQ(track, first);
  const Json sockets = read_json(b / "sockets.json");
  EXPECT_TRUE(sockets["in_place"].get<bool>());
  const std::vector<fs::path> fa = frame_files(a), fb = frame_files(b);
  EXPECT_EQ(fa.size(), fb.size());
  EXPECT_EQ(fa.size(), track["x"].size());
  for (size_t f = 0; f < std::min(fa.size(), fb.size()); ++f) {
    const GroundMotion g{track["x"][f].get<double>(), track["z"][f].get<double>(), track["yaw"][f].get<double>()};
    const Mat4<double> m = ground_matrix(g);
    const PlyFile pa = read_ply(fa[f]), pb = read_ply(fb[f]);
    EXPECT_EQ(vertex_count(pa), vertex_count(pb));
    for (size_t v = 0; v < std::min(vertex_count(pa), vertex_count(pb)); ++v) {
      const Vec3<double> original = vertex(pa, v);
      out.scene = std::max(out.scene, glm::length(original));
      out.worst = std::max(out.worst, glm::length(Vec3<double>(m * glm::dvec4(vertex(pb, v), 1.0)) - original));
    }
    const GroundMotion g0{track["x"][0].get<double>(), track["z"][0].get<double>(), track["yaw"][0].get<double>()};
    out.travelled = std::max(out.travelled, std::hypot(g.x - g0.x, g.z - g0.z));
    out.turned = std::max(out.turned, std::abs(std::remainder(g.yaw - g0.yaw, 2 * M_PI)));
    const GroundMotion left = ground_motion(matrix_of(sockets["sockets"][0]["matrices"][f]));
    out.root_drift = std::max(out.root_drift, std::hypot(left.x, left.z));
    out.root_yaw = std::max(out.root_yaw, std::abs(left.yaw));
  }
  std::printf("%s %s: M(t) · in-place vs normal bake, largest distance %.3g (scene size %.3g); the root travelled %.3g "
              "and turned %.3g rad; in place it stays within %.3g of the origin, heading within %.3g rad\n",
              stem.c_str(), clip.c_str(), out.worst, out.scene, out.travelled, out.turned, out.root_drift, out.root_yaw);
  EXPECT_LT(out.worst, 1e-5 * out.scene);
  EXPECT_LT(out.root_drift, 1e-9 * out.scene);
  EXPECT_LT(out.root_yaw, 1e-9);
  return out;
}

TEST(RootMotion, GeneratedWalkerInPlaceAndTrackGiveBackTheOriginal) {
  const WalkResult r = compare_in_place(model_path("socket_prop.gltf"), "walk", 30);
  EXPECT_GT(r.travelled, 3.6);  // to (3, 2): 1.5 t along x and 0.5 t² along z over 2 s, √13 = 3.606
  EXPECT_GT(r.turned, 2.0);     // 120°
}

// The crossfade tests' legs walk in place but turn the pelvis ±6° (the skin's skeleton): in place takes the
// turn out, and the track gives it back.
TEST(RootMotion, LegsPelvisTurnIsTakenOutAndGivenBack) {
  const WalkResult r = compare_in_place(model_path("walk_run_legs.gltf"), "walk", 30);
  EXPECT_GT(r.turned, 0.1);
}

// The glb frames of an in-place bake show the in-place pose: a viewer composing the written node transforms
// puts every vertex where the in-place PLY frame has it (the glb writer took the ground motion out of the
// scene roots' transforms too). Without that, the vertices would come back to the original place, metres
// away. Tolerance as above, plus the glb's own float rounding of the vertices into their node's space.
TEST(RootMotion, GlbFramesShowTheInPlacePose) {
  const ScratchDir scratch("root_glb");
  BakeOptions o;
  o.plan.out_dir = scratch.path().string();
  o.plan.frames.fps = 4;
  o.formats = unsigned(BakeFormat::kPly) | unsigned(BakeFormat::kGlb);
  o.backend = Backend::kFastCpu;
  o.motion.in_place = true;
  ASSERT_FALSE(bake({model_path("socket_prop.gltf").string()}, o).any_failed());
  const fs::path folder = scratch.path() / "socket_prop" / "walk";
  double worst = 0;
  size_t frames = 0;
  for (const fs::path& ply_path : frame_files(folder)) {
    const PlyFile ply = read_ply(ply_path);
    const Asset glb = load_asset(fs::path(ply_path).replace_extension(".glb").string());
    const Pose pose = sample_pose(glb, nullptr, 0);
    size_t v = 0;
    for (const MeshInstance& instance : mesh_instances(glb, choose_scene(glb, -1)))
      for (const Primitive& p : glb.meshes[size_t(instance.mesh)].primitives)
        for (const glm::vec3& position : p.positions) {
          const Vec3<double> world = Vec3<double>(pose.world[size_t(instance.node)] * glm::dvec4(glm::dvec3(position), 1.0));
          ASSERT_LT(v, vertex_count(ply));
          worst = std::max(worst, glm::length(world - vertex(ply, v++)));
        }
    EXPECT_EQ(v, vertex_count(ply));
    ++frames;
  }
  std::printf("socket_prop in place: glb frames as a viewer composes them vs the PLY frames, largest distance %.3g over %zu frames\n",
              worst, frames);
  EXPECT_EQ(frames, 9u);
  EXPECT_LT(worst, 1e-5);
}

// The shared models' clips walk and run in place already (measured with this test: CesiumMan's root moves
// 9 mm and turns 3° over its clip, the others' roots not at all: Fox's root, the skin's `skeleton`
// _rootJoint, is not animated; BrainStem's and RiggedFigure's move only up and down), so they check that in
// place changes nothing but the ground motion, on real rigs with Z-up roots; socket_prop.gltf is the walker
// that travels and turns.
struct SharedWalker {
  const char* model;
  const char* clip;
  double fps;         // frames a second: enough to cover the clip, few enough for a unit test
  double min_travel;  // how far the root goes (measured), so that a track of zeros would fail CesiumMan
};

class RootMotionShared : public testing::TestWithParam<SharedWalker> {};

TEST_P(RootMotionShared, InPlaceAndTrackGiveBackTheOriginal) {
  const fs::path input = model_path(GetParam().model);
  if (!fs::exists(input)) GTEST_SKIP() << "SKIPPED: " << GetParam().model << " is not among the shared test models";
  const WalkResult r = compare_in_place(input, GetParam().clip, GetParam().fps);
  EXPECT_GE(r.travelled, GetParam().min_travel);
}

INSTANTIATE_TEST_SUITE_P(Models, RootMotionShared,
                         testing::Values(SharedWalker{"CesiumMan/CesiumMan.glb", "animation0", 10, 0.008},
                                         SharedWalker{"Fox/Fox.glb", "Walk", 10, 0},
                                         SharedWalker{"Fox/Fox.glb", "Run", 10, 0},
                                         SharedWalker{"BrainStem/BrainStem.glb", "animation0", 3, 0},
                                         SharedWalker{"RiggedFigure/RiggedFigure.glb", "animation0", 10, 0}),
                         [](const testing::TestParamInfo<SharedWalker>& p) {
                           std::string name = fs::path(p.param.model).stem().string() + "_" + p.param.clip;
                           for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return name;
                         });

}  // namespace
}  // namespace dqskin
