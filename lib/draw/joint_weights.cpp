// The per-vertex influence of one joint, for `dqskin render --shade weights`.
#include "dqskin/renderer.hpp"

#include "dqskin/error.hpp"

#include <algorithm>

namespace dqskin {

std::vector<std::vector<float>> joint_weights(const Asset& asset, const std::vector<MeshInstance>& instances,
                                              const std::string& joint) {
  const auto named = std::find_if(asset.nodes.begin(), asset.nodes.end(), [&](const Node& n) { return n.name == joint; });
  if (named == asset.nodes.end()) throw InputError("--joint '" + joint + "': no node has that name");
  const int node = int(named - asset.nodes.begin());
  std::vector<std::vector<float>> out;
  for (const MeshInstance& inst : instances) {
    // The joint's index in the instance's skin (several entries are allowed; all count), or rigid.
    std::vector<uint16_t> slots;
    if (inst.skin >= 0) {
      const std::vector<int>& joints = asset.skins[size_t(inst.skin)].joints;
      for (size_t j = 0; j < joints.size(); ++j)
        if (joints[j] == node) slots.push_back(uint16_t(j));
    }
    for (const Primitive& p : asset.meshes[size_t(inst.mesh)].primitives) {
      std::vector<float> w(p.vertex_count(), inst.skin < 0 && inst.node == node ? 1.0f : 0.0f);
      const size_t k = size_t(p.influences);
      if (inst.skin >= 0 && k > 0 && !slots.empty()) {
        for (size_t v = 0; v < w.size(); ++v) {
          double sum = 0, mine = 0;  // weights divided by their sum, as the deformers do
          for (size_t i = 0; i < k; ++i) {
            const double weight = double(p.weights[v * k + i]);
            sum += weight;
            if (std::find(slots.begin(), slots.end(), p.joints[v * k + i]) != slots.end()) mine += weight;
          }
          w[v] = sum > 0 ? float(mine / sum) : 0.0f;
        }
      }
      out.push_back(std::move(w));
    }
  }
  return out;
}

}  // namespace dqskin
