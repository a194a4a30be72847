// Holding a float deformer (the GPU path, the fast CPU deformer) to the double-precision CPU reference, the
// oracle (header-only, for the test executables): the models every such test covers, and what it measures.
// Tolerances: positions 1e-5 × the animation's bounding-box diagonal (float keeps 6e-8 relative; the rest
// is the float palette and the blend's rounding), normals and tangents 1e-4 where they are defined.
#pragma once

#include "dqskin/animation.hpp"
#include "dqskin/deformed_batch.hpp"
#include "dqskin/skinning.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace dqskin::testing_support {

// Every generated rig (testdata/) and shared sample model the accuracy tests run.
inline std::vector<std::string> accuracy_model_paths() {
  std::vector<std::string> out;
  for (const char* rig : {"twisted_cylinder", "bending_arm", "uniform_scale", "nonuniform_scale", "eight_influences",
                          "interpolation_modes", "morph_skin", "two_skins"})
    out.push_back(std::string(DQSKIN_TESTDATA_DIR) + "/" + rig + ".gltf");
  for (const char* model : {"RiggedSimple/RiggedSimple.glb", "RiggedFigure/RiggedFigure.glb", "CesiumMan/CesiumMan.glb",
                            "SimpleSkin/SimpleSkin.gltf", "Fox/Fox.glb", "BrainStem/BrainStem.glb",
                            "RecursiveSkeletons/RecursiveSkeletons.glb", "raylib_robot/robot.glb",
                            "raylib_greenman/greenman.glb", "InterpolationTest/InterpolationTest.glb",
                            "AnimatedMorphCube/AnimatedMorphCube.glb", "SimpleMorph/SimpleMorph.gltf"})
    out.push_back(std::string(DQSKIN_SHARED_TESTDATA_DIR) + "/" + model);
  return out;
}

// A deformed normal is only defined where the blended 3×3 does not collapse the surface: LBS of a
// 180° twist (the candy wrapper) maps a ring onto the axis, and there the normal's direction is rounding
// noise in both paths. True when |cof(A) n| ≥ 1e-3 · |A|² (Frobenius) for the vertex's blend A (the LBS
// matrix, or the blended S under dqs).
inline bool well_conditioned_normal(const Asset& asset, const std::vector<MeshInstance>& instances,
                                    size_t flat_primitive, const std::vector<JointTransforms>& skins, size_t v,
                                    BlendMode mode) {
  size_t index = 0;
  for (const MeshInstance& inst : instances) {
    const Mesh& mesh = asset.meshes[size_t(inst.mesh)];
    if (flat_primitive >= index + mesh.primitives.size()) {
      index += mesh.primitives.size();
      continue;
    }
    const Primitive& prim = mesh.primitives[flat_primitive - index];
    if (inst.skin < 0) return true;  // a node's world matrix: invertible in practice
    const JointTransforms& jt = skins[size_t(inst.skin)];
    Mat3<double> a(0.0);
    double sum = 0;
    for (size_t k = 0; k < size_t(prim.influences); ++k) sum += double(prim.weights[v * size_t(prim.influences) + k]);
    if (sum == 0) return true;
    for (size_t k = 0; k < size_t(prim.influences); ++k) {
      const double w = double(prim.weights[v * size_t(prim.influences) + k]) / sum;
      const size_t j = prim.joints[v * size_t(prim.influences) + k];
      a += w * (mode == BlendMode::kLbs ? Mat3<double>(jt.matrices[j]) : jt.scale[j]);
    }
    const Mat3<double> cof(glm::cross(a[1], a[2]), glm::cross(a[2], a[0]), glm::cross(a[0], a[1]));
    const double scale2 = glm::dot(a[0], a[0]) + glm::dot(a[1], a[1]) + glm::dot(a[2], a[2]);  // |A|², as cof(A) is quadratic
    return glm::length(cof * glm::dvec3(prim.normals[v])) >= 1e-3 * scale2;
  }
  return true;
}

// Every clip of `asset`, or the rest pose (null) when it has none.
inline std::vector<const Clip*> clips_or_rest(const Asset& asset) {
  std::vector<const Clip*> v;
  for (const Clip& clip : asset.clips) v.push_back(&clip);
  if (v.empty()) v.push_back(nullptr);
  return v;
}

// The times the accuracy tests deform: every frame at 10 fps, enough to cross every key interval of the
// test models' clips; the rest pose once.
inline std::vector<double> accuracy_times(const Clip* clip, double fps = 10) {
  FrameSpec spec;
  spec.fps = fps;
  return clip ? frame_times(*clip, spec) : std::vector<double>{0.0};
}

// The frame rate of the sweeps that compare a deformer with the reference over every clip of every model:
// 10 fps, and 2 in the sanitizer build (CMakeLists.txt defines DQSKIN_SANITIZER_BUILD). That build looks for memory and undefined-behaviour errors, which
// every code path meets in the first frames as in the last, while the Release build checks the accuracy
// of every frame (BrainStem's eight sweeps took 80 s each under ASan at 10 fps).
#ifdef DQSKIN_SANITIZER_BUILD
inline constexpr double kSweepFps = 2;
#else
inline constexpr double kSweepFps = 10;
#endif

// The largest differences of a float deformer's batch from the reference, frame by frame.
struct AccuracyMeter {
  double worst_position = 0, worst_normal = 0, worst_tangent = 0;
  size_t ill_conditioned = 0;  // normals (and their tangents) left out: undefined in both paths
  glm::dvec3 lo{1e300}, hi{-1e300};  // extent of the animation, for the position tolerance

  double position_tolerance() const { return 1e-5 * glm::distance(lo, hi); }

  // Compares frame `f` of `batch` with the reference at `time`.
  void add(const Asset& asset, const std::vector<MeshInstance>& instances, BlendMode mode, const Clip* clip,
           double time, const DeformedBatch& batch, size_t f) {
    const Pose pose = sample_pose(asset, clip, time);
    std::vector<JointTransforms> skins;
    for (const Skin& skin : asset.skins) skins.push_back(joint_transforms(skin, pose));
    const DeformedFrame cpu = deform_frame(asset, instances, pose, mode);
    if (cpu.primitives.size() != batch.primitives.size()) {
      worst_position = 1e300;  // fails every tolerance
      return;
    }
    for (size_t p = 0; p < cpu.primitives.size(); ++p) {
      const DeformedBatch::Primitive& g = batch.primitives[p];
      const DeformedPrimitive& r = cpu.primitives[p];
      for (size_t v = 0; v < g.vertices; ++v) {
        const size_t o = (f * g.vertices + v) * 3;
        worst_position = std::max(worst_position, glm::distance(glm::dvec3(g.positions[o], g.positions[o + 1], g.positions[o + 2]),
                                                                r.positions[v]));
        lo = glm::min(lo, r.positions[v]);
        hi = glm::max(hi, r.positions[v]);
        if (r.normals.empty()) continue;
        if (!well_conditioned_normal(asset, instances, p, skins, v, mode)) {
          ++ill_conditioned;
          continue;
        }
        worst_normal = std::max(worst_normal, glm::distance(glm::dvec3(g.normals[o], g.normals[o + 1], g.normals[o + 2]),
                                                            r.normals[v]));
        if (r.tangents.empty() || g.tangents.empty()) continue;
        const size_t t = (f * g.vertices + v) * 4;
        worst_tangent = std::max(worst_tangent, glm::distance(glm::dvec3(g.tangents[t], g.tangents[t + 1], g.tangents[t + 2]),
                                                              glm::dvec3(r.tangents[v])));
      }
    }
  }
};

}  // namespace dqskin::testing_support
