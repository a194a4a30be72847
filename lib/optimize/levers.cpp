#include "levers.hpp"

#include "dqskin/animation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

namespace dqskin::optimize_detail {
namespace {

// An upper bound of the largest singular value of a 3×3: its Frobenius norm (at most √3 times too large).
double norm3(const Mat4<double>& m) {
  double s = 0;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) s += m[c][r] * m[c][r];
  return std::sqrt(s);
}

Vec3<double> origin(const Mat4<double>& m) { return {m[3][0], m[3][1], m[3][2]}; }

}  // namespace

Levers compute_levers(const Asset& asset, const std::vector<MeshInstance>& instances, BlendMode mode) {
  Levers levers;
  levers.nodes.resize(asset.nodes.size());
  const Pose rest = sample_pose(asset, nullptr, 0.0);
  const DeformedFrame frame = deform_frame(asset, instances, rest, mode);

  Vec3<double> lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  std::set<std::vector<int>> sets;
  std::vector<int> chain;
  // Walks from `node` to the root, widening each node's levers for vertex `p`, and adds the nodes to `chain`.
  auto climb = [&](int node, const Vec3<double>& p) {
    for (int n = node; n >= 0; n = asset.nodes[size_t(n)].parent) {
      NodeLevers& l = levers.nodes[size_t(n)];
      const double reach = glm::length(p - origin(rest.world[size_t(n)]));
      l.moves_vertices = true;
      l.rotation = std::max(l.rotation, reach);
      const int parent = asset.nodes[size_t(n)].parent;
      l.translation = std::max(l.translation, parent >= 0 ? norm3(rest.world[size_t(parent)]) : 1.0);
      const Vec3<double>& s = asset.nodes[size_t(n)].local.scale;
      const double smallest = std::max(1e-3, std::min({std::abs(s.x), std::abs(s.y), std::abs(s.z)}));
      l.scale = std::max(l.scale, reach / smallest);
      chain.push_back(n);
    }
  };

  size_t at = 0;
  for (const MeshInstance& instance : instances) {
    const Mesh& mesh = asset.meshes[size_t(instance.mesh)];
    const Skin* skin = instance.skin >= 0 ? &asset.skins[size_t(instance.skin)] : nullptr;
    for (const Primitive& primitive : mesh.primitives) {
      const DeformedPrimitive& deformed = frame.primitives[at++];
      const size_t influences = size_t(primitive.influences);
      for (size_t v = 0; v < deformed.positions.size(); ++v) {
        const Vec3<double>& p = deformed.positions[v];
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
        chain.clear();
        if (skin && influences > 0) {
          for (size_t k = 0; k < influences; ++k)
            if (primitive.weights[v * influences + k] > 0)
              climb(skin->joints[primitive.joints[v * influences + k]], p);
        } else {
          climb(instance.node, p);
        }
        std::sort(chain.begin(), chain.end());
        chain.erase(std::unique(chain.begin(), chain.end()), chain.end());
        if (!primitive.targets.empty()) chain.push_back(-1 - instance.node);  // its morph weights
        sets.insert(chain);
      }
      // Morph targets: each target's largest displacement, through the largest scale that reaches the mesh.
      if (!primitive.targets.empty()) {
        double scale = norm3(rest.world[size_t(instance.node)]);
        if (skin) {
          scale = 0;
          for (size_t j = 0; j < skin->joints.size(); ++j)
            scale = std::max(scale, norm3(rest.world[size_t(skin->joints[j])] * skin->inverse_bind[j]));
        }
        std::vector<double>& w = levers.nodes[size_t(instance.node)].weights;
        w.resize(std::max(w.size(), primitive.targets.size()), 0.0);
        for (size_t t = 0; t < primitive.targets.size(); ++t)
          for (const glm::vec3& d : primitive.targets[t].positions)
            w[t] = std::max(w[t], scale * double(glm::length(d)));
      }
    }
  }
  levers.dependency_sets.assign(sets.begin(), sets.end());
  levers.diagonal = lo.x <= hi.x ? glm::length(hi - lo) : 0.0;
  return levers;
}

}  // namespace dqskin::optimize_detail
