// Rest data and palettes in the fast CPU kernel's layout.
#include "fast_rest_data.hpp"

#include "dqskin/error.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace dqskin::deform {
namespace {

size_t blocks_for(size_t vertices) { return (vertices + kLanes - 1) / kLanes; }

// Component c of each vertex of `src` into a padded array.
template <typename Vec>
void scatter(const std::vector<Vec>& src, int c, float* dst) {
  for (size_t v = 0; v < src.size(); ++v) dst[v] = src[v][c];
}

RestPrimitive make_primitive(const Asset& asset, const MeshInstance& inst, size_t instance_index, const Primitive& src) {
  if (src.influences > kMaxInfluences)  // the Asset's contract (asset.hpp); the loader never makes more
    throw std::invalid_argument("make_rest_data: more than kMaxInfluences influences per vertex");
  RestPrimitive r;
  r.instance = instance_index;
  r.vertices = src.vertex_count();
  const size_t blocks = blocks_for(r.vertices), padded = blocks * kLanes;
  const bool skinned = inst.skin >= 0;
  const size_t joint_count = skinned ? asset.skins[size_t(inst.skin)].joints.size() : 1;
  const int32_t identity = int32_t(joint_count);  // the palette's last entry
  const size_t k_count = skinned ? std::max<size_t>(1, size_t(src.influences)) : 1;
  const bool normals = !src.normals.empty(), tangents = !src.tangents.empty();

  const size_t arrays = 3 + (normals ? 3u : 0u) + (tangents ? 4u : 0u) + k_count;
  r.arrays.assign(arrays * padded, 0.0f);
  r.joints.assign(k_count * padded, identity);
  float* next = r.arrays.data();
  // The next padded array, filled with component c of `src`.
  auto take = [&](const auto& from, int c) {
    float* a = next;
    next += padded;
    scatter(from, c, a);
    return a;
  };

  KernelPrimitive& view = r.view;
  view.blocks = blocks;
  view.influences = k_count;
  for (int c = 0; c < 3; ++c) view.position[c] = take(src.positions, c);
  if (normals)
    for (int c = 0; c < 3; ++c) view.normal[c] = take(src.normals, c);
  if (tangents)
    for (int c = 0; c < 4; ++c) view.tangent[c] = take(src.tangents, c);
  float* weights = next;
  view.weight = weights;
  view.joint = r.joints.data();

  // Influences as the reference gathers them, the largest (the first of equals) moved to k = 0. Padding
  // lanes and weightless vertices read the identity with weight 1.
  for (size_t v = 0; v < padded; ++v) {
    int32_t joint[kMaxInfluences];
    double weight[kMaxInfluences], sum = 0;
    size_t count = 0;
    if (!skinned && v < r.vertices) {
      joint[0] = 0, weight[0] = 1, sum = 1, count = 1;
    } else if (v < r.vertices) {
      for (size_t k = 0; k < size_t(src.influences); ++k) {
        const float w = src.weights[v * size_t(src.influences) + k];
        if (!(w > 0)) continue;
        const uint16_t j = src.joints[v * size_t(src.influences) + k];
        if (j >= joint_count)
          throw InputError("a vertex names joint " + std::to_string(j) + " of a skin with " + std::to_string(joint_count) +
                           " joints");
        joint[count] = int32_t(j), weight[count] = double(w), sum += double(w), ++count;
      }
    }
    if (count == 0) {
      joint[0] = identity, weight[0] = 1, sum = 1, count = 1;
    }
    const size_t largest = size_t(std::max_element(weight, weight + count) - weight);
    std::swap(joint[0], joint[largest]);
    std::swap(weight[0], weight[largest]);
    for (size_t k = 0; k < count; ++k) {
      r.joints[k * padded + v] = joint[k];
      weights[k * padded + v] = float(weight[k] / sum);
    }
  }

  // Morph offsets: one padded array per component of each part a target has.
  for (const MorphTarget& target : src.targets) {
    const std::vector<glm::vec3>* parts[3] = {&target.positions, normals ? &target.normals : nullptr,
                                              tangents ? &target.tangents : nullptr};
    for (const std::vector<glm::vec3>* part : parts) {
      if (!part || part->empty()) {
        r.morph_pointers.push_back(nullptr);
        continue;
      }
      std::vector<float>& a = r.morph.emplace_back(3 * padded, 0.0f);
      for (int c = 0; c < 3; ++c) scatter(*part, c, a.data() + size_t(c) * padded);
      r.morph_pointers.push_back(a.data());
    }
  }
  view.targets = src.targets.size();
  view.morph = r.morph_pointers.data();
  return r;
}

}  // namespace

std::vector<RestPrimitive> make_rest_data(const Asset& asset, const std::vector<MeshInstance>& instances) {
  std::vector<RestPrimitive> out;
  for (size_t i = 0; i < instances.size(); ++i)
    for (const Primitive& prim : asset.meshes[size_t(instances[i].mesh)].primitives)
      out.push_back(make_primitive(asset, instances[i], i, prim));
  return out;
}

KernelMode pack_palette(const JointTransforms& joints, BlendMode mode, std::vector<float>& palette) {
  const size_t count = joints.matrices.size();
  palette.assign((count + 1) * kPaletteStride, 0.0f);
  const bool lbs = mode == BlendMode::kLbs;
  for (size_t j = 0; j < count; ++j) {
    float* e = &palette[j * kPaletteStride];
    if (lbs) {
      const Mat4<double>& m = joints.matrices[j];
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) e[c * 3 + r] = float(m[c][r]);
      continue;
    }
    const DualQuat<double>& q = joints.rigid[j];
    const Mat3<double>& s = joints.scale[j];
    const double values[14] = {q.real.x, q.real.y, q.real.z, q.real.w, q.dual.x, q.dual.y, q.dual.z,
                               q.dual.w, s[0][0], s[1][0], s[2][0], s[1][1], s[2][1], s[2][2]};
    for (int k = 0; k < 14; ++k) e[k] = float(values[k]);
  }
  // The identity: [I | 0], or the unit dual quaternion with S = I.
  float* id = &palette[count * kPaletteStride];
  if (lbs) {
    id[0] = id[4] = id[8] = 1;
  } else {
    id[3] = 1;
    id[8] = id[11] = id[13] = 1;
  }
  if (lbs) return KernelMode::kLbs;
  return joints.any_non_rigid ? KernelMode::kDqsScale : KernelMode::kDqs;
}

}  // namespace dqskin::deform
