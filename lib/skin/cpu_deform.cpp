// The CPU reference deformer, in double precision: morph targets, then LBS, DQS (DLB with the two-phase
// scale rule of docs/DESIGN.md §3.6; Kavan et al. 2008) or DIB (Kavan et al. §4).
#include "dqskin/skinning.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <thread>

namespace dqskin {
namespace {

using DVec4 = glm::vec<4, double, glm::defaultp>;

// det(A) · A⁻ᵀ from the columns: the normal transform that needs no inverse.
Mat3<double> cofactor(const Mat3<double>& a) {
  return Mat3<double>(glm::cross(a[1], a[2]), glm::cross(a[2], a[0]), glm::cross(a[0], a[1]));
}

Vec3<double> unit_or(const Vec3<double>& v, const Vec3<double>& fallback) {
  const double length = glm::length(v);
  return length > 0 ? v / length : fallback;
}

// A vertex's influences with weight: every JOINTS_n/WEIGHTS_n set the file has (up to kMaxInfluences).
struct Influences {
  size_t count = 0;
  int joint[kMaxInfluences];
  double weight[kMaxInfluences];  // divided by their sum
};

Influences gather(const Primitive& prim, size_t v) {
  Influences in;
  double sum = 0;
  const size_t k0 = v * size_t(prim.influences);
  for (size_t k = 0; k < size_t(prim.influences); ++k) {
    const float w = prim.weights[k0 + k];
    if (w > 0) {
      in.joint[in.count] = prim.joints[k0 + k];
      in.weight[in.count] = double(w);
      sum += double(w);
      ++in.count;
    }
  }
  for (size_t k = 0; k < in.count; ++k) in.weight[k] /= sum;
  return in;
}

struct VertexTransform {
  // v' = rigid(S v) for dual-quaternion modes; v' = M v for matrices (then rigid is unused).
  bool is_matrix = true;
  Mat4<double> matrix{1.0};
  DualQuat<double> rigid;
  Mat3<double> scale{1.0};
};

VertexTransform blend(const Influences& in, const JointTransforms& jt, BlendMode mode) {
  VertexTransform x;
  if (mode == BlendMode::kLbs) {
    x.matrix = Mat4<double>(0.0);
    for (size_t k = 0; k < in.count; ++k) x.matrix += jt.matrices[size_t(in.joint[k])] * in.weight[k];
    return x;
  }
  x.is_matrix = false;
  // DLB over every influence [Kavan §4], each flipped to the heaviest's hemisphere (blend_dlb).
  DualQuat<double> q[kMaxInfluences];
  for (size_t k = 0; k < in.count; ++k) q[k] = jt.rigid[size_t(in.joint[k])];
  const std::span<const DualQuat<double>> qs(q, in.count);
  const std::span<const double> ws(in.weight, in.count);
  x.rigid = mode == BlendMode::kDqs ? blend_dlb(qs, ws) : blend_dib(qs, ws).blend;
  if (jt.any_non_rigid) {  // two-phase: S blended linearly, applied before the rigid blend
    x.scale = Mat3<double>(0.0);
    for (size_t k = 0; k < in.count; ++k) x.scale += jt.scale[size_t(in.joint[k])] * in.weight[k];
  }
  return x;
}

void deform_range(const Primitive& prim, std::span<const double> morph, const VertexTransform* rigid_instance,
                  const JointTransforms* jt, BlendMode mode, size_t begin, size_t end, DeformedPrimitive& out) {
  const bool has_normals = !out.normals.empty(), has_tangents = !out.tangents.empty();
  for (size_t v = begin; v < end; ++v) {
    // Morph targets first (§3.7.2.2): base + Σ weight · offset.
    Vec3<double> p(prim.positions[v]);
    Vec3<double> n = has_normals ? Vec3<double>(prim.normals[v]) : Vec3<double>(0);
    Vec3<double> t = has_tangents ? Vec3<double>(prim.tangents[v]) : Vec3<double>(0);
    for (size_t k = 0; k < morph.size() && k < prim.targets.size(); ++k) {
      const MorphTarget& target = prim.targets[k];
      if (morph[k] == 0) continue;
      if (!target.positions.empty()) p += morph[k] * Vec3<double>(target.positions[v]);
      if (has_normals && !target.normals.empty()) n += morph[k] * Vec3<double>(target.normals[v]);
      if (has_tangents && !target.tangents.empty()) t += morph[k] * Vec3<double>(target.tangents[v]);
    }

    VertexTransform x;
    bool bind_pose = false;
    if (rigid_instance) {
      x = *rigid_instance;
    } else {
      const Influences in = gather(prim, v);
      if (in.count == 0) bind_pose = true;
      else x = blend(in, *jt, mode);
    }

    if (!bind_pose) {
      if (x.is_matrix) {
        const Mat3<double> a(x.matrix);
        p = Vec3<double>(x.matrix * DVec4(p, 1));
        if (has_normals) n = cofactor(a) * n;
        if (has_tangents) t = a * t;
      } else {
        p = transform_point(x.rigid, x.scale * p);
        if (has_normals) n = rotate_vector(x.rigid, cofactor(x.scale) * n);
        if (has_tangents) t = rotate_vector(x.rigid, x.scale * t);
      }
    }
    out.positions[v] = p;
    if (has_normals) out.normals[v] = unit_or(n, Vec3<double>(prim.normals[v]));
    if (has_tangents)
      out.tangents[v] = DVec4(unit_or(t, Vec3<double>(prim.tangents[v])), double(prim.tangents[v].w));
  }
}

}  // namespace

DeformedPrimitive deform_primitive(const Asset& asset, const MeshInstance& instance, size_t primitive,
                                   const Pose& pose, const JointTransforms* joints, BlendMode mode, int threads,
                                   DeformedOutputs outputs) {
  const Primitive& prim = asset.meshes[size_t(instance.mesh)].primitives[primitive];
  if (prim.influences > kMaxInfluences)  // the Asset's contract (asset.hpp); the loader never makes more
    throw std::invalid_argument("deform_primitive: more than kMaxInfluences influences per vertex");
  const size_t n = prim.vertex_count();
  DeformedPrimitive out;
  out.positions.resize(n);
  // deform_range computes what `out` has room for.
  if (outputs == DeformedOutputs::kAll && !prim.normals.empty()) out.normals.resize(n);
  if (outputs == DeformedOutputs::kAll && !prim.tangents.empty()) out.tangents.resize(n);

  VertexTransform rigid;
  const bool skinned = instance.skin >= 0 && joints;
  if (!skinned) rigid.matrix = pose.world[size_t(instance.node)];
  const std::span<const double> morph(pose.weights[size_t(instance.node)]);

  // Each vertex is independent, so any split gives the same bits.
  const size_t workers = std::clamp<size_t>(size_t(std::max(threads, 1)), 1, std::max<size_t>(1, n / 2048));
  const size_t chunk = (n + workers - 1) / workers;
  std::vector<std::thread> pool;
  for (size_t w = 1; w < workers; ++w)
    pool.emplace_back(deform_range, std::cref(prim), morph, skinned ? nullptr : &rigid, joints, mode, w * chunk,
                      std::min(n, (w + 1) * chunk), std::ref(out));
  deform_range(prim, morph, skinned ? nullptr : &rigid, joints, mode, 0, std::min(n, chunk), out);
  for (std::thread& t : pool) t.join();
  return out;
}

DeformedFrame deform_frame(const Asset& asset, const std::vector<MeshInstance>& instances, const Pose& pose,
                           BlendMode mode, int threads, DeformedOutputs outputs) {
  DeformedFrame frame;
  std::vector<JointTransforms> skins(asset.skins.size());
  std::vector<char> computed(asset.skins.size(), 0);
  for (const MeshInstance& inst : instances) {
    const JointTransforms* jt = nullptr;
    if (inst.skin >= 0) {
      if (!computed[size_t(inst.skin)]) {
        skins[size_t(inst.skin)] = joint_transforms(asset.skins[size_t(inst.skin)], pose);
        computed[size_t(inst.skin)] = 1;
      }
      jt = &skins[size_t(inst.skin)];
    }
    for (size_t p = 0; p < asset.meshes[size_t(inst.mesh)].primitives.size(); ++p)
      frame.primitives.push_back(deform_primitive(asset, inst, p, pose, jt, mode, threads, outputs));
  }
  return frame;
}

std::vector<std::string> weight_warnings(const Asset& asset) {
  std::vector<std::string> out;
  for (size_t m = 0; m < asset.meshes.size(); ++m) {
    for (size_t p = 0; p < asset.meshes[m].primitives.size(); ++p) {
      const Primitive& prim = asset.meshes[m].primitives[p];
      if (prim.influences == 0) continue;
      size_t off = 0, zero = 0;
      double worst = 0;
      for (size_t v = 0; v < prim.vertex_count(); ++v) {
        double sum = 0;
        for (size_t k = 0; k < size_t(prim.influences); ++k) sum += double(prim.weights[v * size_t(prim.influences) + k]);
        if (sum == 0) ++zero;
        else if (std::abs(sum - 1) > 1e-3) ++off, worst = std::max(worst, std::abs(sum - 1));
      }
      const std::string where = "mesh " + std::to_string(m) + " primitive " + std::to_string(p) + ": ";
      if (off)
        out.push_back(where + std::to_string(off) + " vertices have weights that do not sum to 1 (off by up to " +
                      std::to_string(worst) + "); they are renormalized");
      if (zero) out.push_back(where + std::to_string(zero) + " vertices have no weight; they stay in the bind pose");
    }
  }
  return out;
}

}  // namespace dqskin
