// Joint transforms and the CPU reference deformer (docs/DESIGN.md §2.3, §3.7). The CPU
// deformer runs in double precision: it is the oracle every GPU path is compared with.
#pragma once

#include "dqskin/animation.hpp"
#include "dqskin/asset.hpp"

#include <string>
#include <vector>

namespace dqskin {

// One skin at one frame: per joint, in the skin's `joints` order.
struct JointTransforms {
  std::vector<Mat4<double>> matrices;   // joint matrix world(joint) · inverseBind(joint)
  std::vector<DualQuat<double>> rigid;  // its rigid part [R | t] (unit, w ≥ 0 as from_rigid_matrix)
  std::vector<Mat3<double>> scale;      // its symmetric S (A = R S); identity for rigid joints
  bool any_non_rigid = false;           // some joint has scale or shear beyond 1e-5 (docs/DESIGN.md §3.6)
};

JointTransforms joint_transforms(const Skin& skin, const Pose& pose);

// The blend modes of docs/DESIGN.md §3.5: lbs (linear blend of matrices), dqs (DLB with the two-phase scale
// rule), dib (iterative dual-quaternion blending, exact).
enum class BlendMode { kLbs, kDqs, kDib };
const char* to_string(BlendMode mode);
bool parse_blend_mode(const std::string& text, BlendMode& mode);

// A mesh drawn by a node of the scene, in scene order (depth first, children in order). A mesh drawn by
// several nodes appears once per node.
struct MeshInstance {
  int node = -1;
  int mesh = -1;
  int skin = -1;  // -1: the node's world matrix moves the mesh rigidly
};
std::vector<MeshInstance> mesh_instances(const Asset& asset, int scene);

// The "palette" of one mesh instance at `pose`: its skin's joint transforms, or for a rigid instance
// those of a one-joint skin whose joint matrix is the node's world matrix (docs/DESIGN.md §2.1).
JointTransforms instance_joint_transforms(const Asset& asset, const MeshInstance& instance, const Pose& pose);

// The scene a command works on: `requested` when ≥ 0, else the file's default scene, else scene 0;
// -1 when the file has no scenes (then every root node counts). Throws InputError for a bad request.
int choose_scene(const Asset& asset, int requested);

struct DeformedPrimitive {
  std::vector<Vec3<double>> positions;
  std::vector<Vec3<double>> normals;                   // unit; empty when the primitive has none
  std::vector<glm::vec<4, double, glm::defaultp>> tangents;  // xyz unit, w handedness; empty when none
};

// Every primitive of every instance at one pose, instances in order, primitives in mesh order.
struct DeformedFrame {
  std::vector<DeformedPrimitive> primitives;
};

// Deforms one primitive of `instance` at `pose` (morph targets first, then skinning; glTF 2.0 §3.7.3).
// Weights are divided by their sum; a vertex whose weights sum to zero stays at its bind-space position.
// Normals use the cofactor of the blended 3×3 (det · A⁻ᵀ, defined even for singular A); tangents the
// matrix itself, keeping their handedness w. `joints` is the skin's transforms (ignored for rigid
// instances). Vertices are split across `threads` threads; the result does not depend on their number.
// With kPositions, normals and tangents are left empty (a measurement of the surface needs only positions).
enum class DeformedOutputs { kAll, kPositions };
DeformedPrimitive deform_primitive(const Asset& asset, const MeshInstance& instance, size_t primitive,
                                   const Pose& pose, const JointTransforms* joints, BlendMode mode, int threads = 1,
                                   DeformedOutputs outputs = DeformedOutputs::kAll);

DeformedFrame deform_frame(const Asset& asset, const std::vector<MeshInstance>& instances, const Pose& pose,
                           BlendMode mode, int threads = 1, DeformedOutputs outputs = DeformedOutputs::kAll);

// Warnings about skin weights that the deformer corrects (one per primitive): sums away from 1, and
// vertices with no weight at all.
std::vector<std::string> weight_warnings(const Asset& asset);

}  // namespace dqskin
