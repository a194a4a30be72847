// The VAT and DQ crossfade models (docs/DESIGN.md §3.10): what a runtime can compute from two baked frames.
#include "crossfade.hpp"

#include <array>
#include <stdexcept>

namespace dqskin {
namespace {

using DVec4 = glm::vec<4, double, glm::defaultp>;

template <typename V>
V lerp(const V& a, const V& b, double w) {
  return (1 - w) * a + w * b;
}

Vec3<double> lerp_direction(const Vec3<double>& a, const Vec3<double>& b, double w) {
  const Vec3<double> v = lerp(a, b, w);
  const double length = glm::length(v);
  return length > 0 ? v / length : a;
}

// [R | t]·S: the joint matrix whose split is (rigid, scale).
Mat4<double> joint_matrix(const DualQuat<double>& rigid, const Mat3<double>& scale) {
  return to_rigid_matrix(rigid) * Mat4<double>(scale);
}

}  // namespace

DeformedPrimitive vat_crossfade(const DeformedPrimitive& a, const DeformedPrimitive& b, double w) {
  if (a.positions.size() != b.positions.size() || a.normals.size() != b.normals.size() ||
      a.tangents.size() != b.tangents.size())
    throw std::invalid_argument("vat_crossfade: the two frames have different vertex counts");
  DeformedPrimitive out;
  out.positions.resize(a.positions.size());
  out.normals.resize(a.normals.size());
  out.tangents.resize(a.tangents.size());
  for (size_t v = 0; v < a.positions.size(); ++v) out.positions[v] = lerp(a.positions[v], b.positions[v], w);
  for (size_t v = 0; v < a.normals.size(); ++v) out.normals[v] = lerp_direction(a.normals[v], b.normals[v], w);
  for (size_t v = 0; v < a.tangents.size(); ++v)
    out.tangents[v] = DVec4(lerp_direction(Vec3<double>(a.tangents[v]), Vec3<double>(b.tangents[v]), w), a.tangents[v].w);
  return out;
}

DeformedFrame vat_crossfade(const DeformedFrame& a, const DeformedFrame& b, double w) {
  if (a.primitives.size() != b.primitives.size())
    throw std::invalid_argument("vat_crossfade: the two frames have different primitives");
  DeformedFrame out;
  for (size_t p = 0; p < a.primitives.size(); ++p)
    out.primitives.push_back(vat_crossfade(a.primitives[p], b.primitives[p], w));
  return out;
}

JointTransforms dq_crossfade(const JointTransforms& a, const JointTransforms& b, double w) {
  const size_t n = a.rigid.size();
  if (b.rigid.size() != n || a.scale.size() != n || b.scale.size() != n)
    throw std::invalid_argument("dq_crossfade: the two palettes have different joint counts");
  JointTransforms out;
  out.rigid.resize(n);
  out.scale.resize(n);
  out.matrices.resize(n);
  out.any_non_rigid = a.any_non_rigid || b.any_non_rigid;
  const std::array<double, 2> weights = {1 - w, w};
  for (size_t j = 0; j < n; ++j) {
    // DLB of two [Kavan §4] with blend_dlb's pivot, the heavier of the two (A on a tie): the deformer's
    // antipodality rule (docs/DESIGN.md §3.5). Either pivot gives the same pose; this one keeps the bits
    // of A at w = 0 and of B at w = 1 up to the normalization's rounding.
    const std::array<DualQuat<double>, 2> q = {a.rigid[j], b.rigid[j]};
    out.rigid[j] = blend_dlb(std::span<const DualQuat<double>>(q), std::span<const double>(weights));
    // S lerped, like the two-phase rule's Σ w S (§3.6); identity when both are.
    out.scale[j] = lerp(a.scale[j], b.scale[j], w);
    out.matrices[j] = joint_matrix(out.rigid[j], out.scale[j]);
  }
  return out;
}

DeformedFrame dq_crossfade_frame(const Asset& asset, const std::vector<MeshInstance>& instances, const Pose& a,
                                 const Pose& b, double w, BlendMode mode) {
  // The pose deform_primitive reads besides the joints: morph weights (lerped) and, for a rigid
  // instance, its node's world matrix (set below to the blended one).
  Pose blended = a;
  for (size_t i = 0; i < blended.weights.size() && i < b.weights.size(); ++i)
    for (size_t k = 0; k < blended.weights[i].size() && k < b.weights[i].size(); ++k)
      blended.weights[i][k] = lerp(a.weights[i][k], b.weights[i][k], w);

  DeformedFrame frame;
  for (const MeshInstance& inst : instances) {
    const JointTransforms joints =
        dq_crossfade(instance_joint_transforms(asset, inst, a), instance_joint_transforms(asset, inst, b), w);
    if (inst.skin < 0) blended.world[size_t(inst.node)] = joints.matrices[0];
    for (size_t p = 0; p < asset.meshes[size_t(inst.mesh)].primitives.size(); ++p)
      frame.primitives.push_back(deform_primitive(asset, inst, p, blended, &joints, mode));
  }
  return frame;
}

}  // namespace dqskin
