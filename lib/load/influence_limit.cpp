// --max-influences: see influence_limit.hpp. The order (weight descending, then joint ascending) and the
// renormalization are lib/lint/lint_fix.cpp's, so that both give the same float weights.
#include "influence_limit.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace dqskin::gltf {
namespace {

struct Influence {
  uint16_t joint;
  double weight;
};

// The vertex's influences with weight, merged per joint, in kept order, cut to `keep`, renormalized.
void fixed_influences(const Primitive& prim, size_t v, size_t keep, std::vector<Influence>& in) {
  in.clear();
  const size_t per = size_t(prim.influences);
  for (size_t k = 0; k < per; ++k) {
    const float w = prim.weights[v * per + k];
    if (!(w > 0)) continue;
    const uint16_t j = prim.joints[v * per + k];
    auto same = std::find_if(in.begin(), in.end(), [&](const Influence& i) { return i.joint == j; });
    if (same != in.end())
      same->weight += double(w);
    else
      in.push_back({j, double(w)});
  }
  std::stable_sort(in.begin(), in.end(), [](const Influence& a, const Influence& b) {
    return a.weight != b.weight ? a.weight > b.weight : a.joint < b.joint;
  });
  if (in.size() > keep) in.resize(keep);
  double sum = 0;
  for (const Influence& i : in) sum += i.weight;
  for (Influence& i : in) i.weight = double(float(i.weight / sum));
  in.erase(std::remove_if(in.begin(), in.end(), [](const Influence& i) { return i.weight == 0; }), in.end());
}

// Whether some vertex has more than `keep` distinct joints with weight.
bool exceeds(const Primitive& prim, size_t keep) {
  const size_t per = size_t(prim.influences);
  if (per <= keep) return false;
  std::vector<uint16_t> joints;
  for (size_t v = 0; v < prim.vertex_count(); ++v) {
    joints.clear();
    for (size_t k = 0; k < per; ++k)
      if (prim.weights[v * per + k] > 0) joints.push_back(prim.joints[v * per + k]);
    std::sort(joints.begin(), joints.end());
    if (size_t(std::unique(joints.begin(), joints.end()) - joints.begin()) > keep) return true;
  }
  return false;
}

void limit(Primitive& prim, size_t keep) {
  const size_t n = prim.vertex_count();
  std::vector<Influence> in;
  size_t most = 1;
  for (size_t v = 0; v < n; ++v) {
    fixed_influences(prim, v, keep, in);
    most = std::max(most, in.size());
  }
  const size_t per = (most + 3) / 4 * 4;
  std::vector<uint16_t> joints(n * per, 0);
  std::vector<float> weights(n * per, 0.0f);
  for (size_t v = 0; v < n; ++v) {
    fixed_influences(prim, v, keep, in);
    for (size_t k = 0; k < in.size(); ++k) {
      joints[v * per + k] = in[k].joint;
      weights[v * per + k] = float(in[k].weight);
    }
  }
  prim.influences = int(per);
  prim.joints = std::move(joints);
  prim.weights = std::move(weights);
}

}  // namespace

void keep_largest_influences(Asset& asset, int max_influences) {
  if (max_influences < 1) return;
  for (Mesh& mesh : asset.meshes)
    for (Primitive& prim : mesh.primitives)
      if (prim.influences > 0 && exceeds(prim, size_t(max_influences))) limit(prim, size_t(max_influences));
}

}  // namespace dqskin::gltf
