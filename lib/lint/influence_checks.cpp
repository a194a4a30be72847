// The per-vertex checks of `dqskin lint` over every JOINTS_n/WEIGHTS_n set of a primitive (glTF 2.0
// §3.7.3.3: weights are non-negative and sum to 1; a joint index is below the skin's joint count; the
// Khronos validator also refuses the same joint twice in a vertex), and the joints no vertex uses.
#include "lint_checks.hpp"

#include "dqskin/job.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

namespace dqskin::lint {

std::string primitive_name(const gltf::SkinnedPrimitive& p) {
  std::string s = "mesh ";
  s += std::to_string(p.mesh);
  s += " primitive ";
  s += std::to_string(p.primitive);
  return s;
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

double normalized_max(int component) {
  switch (component) {
    case 5120: return 127;    // byte
    case 5121: return 255;    // unsigned byte
    case 5122: return 32767;  // short
    case 5123: return 65535;  // unsigned short
    default: return 0;
  }
}

JointRange joint_range(const gltf::SkinnedPrimitive& p, const Asset& asset) {
  JointRange r;
  for (size_t k = 0; k < p.skins.size(); ++k) {
    const size_t n = asset.skins[size_t(p.skins[k])].joints.size();
    if (k == 0 || n < r.fewest) r.fewest = n, r.smallest = p.skins[k];
    if (k == 0 || n > r.most) r.most = n, r.largest = p.skins[k];
  }
  return r;
}

namespace {

struct Influence {
  uint32_t joint;
  double weight;
  double rounding;  // half a stored unit: 0.5/255, 0.5/65535, or 0 for float
};

void check_vertex(const gltf::SkinnedPrimitive& p, size_t v, const std::vector<Influence>& in, const JointRange& range,
                  const LintOptions& o, Findings& out) {
  const std::string where = primitive_name(p);
  auto example = [&](long long joint, double value) {
    LintExample e;
    e.where = where;
    e.vertex = static_cast<long long>(v);
    e.joint = joint;
    e.value = value;
    return e;
  };
  auto at = [&] { return " at " + where + " vertex " + std::to_string(v); };

  double sum = 0, most_negative = 0;
  long long negative_joint = -1;
  size_t positive = 0;
  for (const Influence& i : in) {
    sum += i.weight;
    if (i.weight > 0) ++positive;
    if (i.weight < most_negative) most_negative = i.weight, negative_joint = i.joint;
  }
  double rounding = 0;
  for (const Influence& i : in)
    if (i.weight != 0) rounding += i.rounding;
  const double allowed = std::max(o.sum_tolerance, rounding);

  if (most_negative < 0)
    out["negative-weight"].add(-most_negative, example(negative_joint, most_negative), [&] {
      return "weight " + number(most_negative) + " on joint " + std::to_string(negative_joint) + at();
    });
  if (positive == 0) {
    out["zero-weight-vertex"].add(0, example(-1, 0), [&] { return "no joint has weight" + at(); });
  } else if (std::abs(sum - 1) > allowed) {
    out["weight-sum"].add(std::abs(sum - 1), example(-1, sum), [&] {
      return "weights sum to " + number(sum) + " (1 ± " + number(allowed) + " allowed)" + at();
    });
  }
  // Both are about runtimes that drop influences (three.js reads JOINTS_0 only, Babylon.js JOINTS_0 and
  // JOINTS_1; dqskin reads every set), so neither fires within --max-influences, the runtime's own count.
  if (positive > 8 && positive > size_t(o.max_influences)) {
    out["over-8-influences"].add(double(positive), example(-1, double(positive)), [&] {
      return std::to_string(positive) + " joints with weight (Babylon.js reads 8, three.js 4; they drop the rest)" +
             at();
    });
  } else if (positive > size_t(o.max_influences)) {
    out["too-many-influences"].add(double(positive), example(-1, double(positive)), [&] {
      return std::to_string(positive) + " joints with weight (more than " + std::to_string(o.max_influences) + ")" +
             at();
    });
  }
  // Counted once per vertex (its worst case), as the other checks count vertices, however many slots share
  // the problem. At most 32 influences (8 sets, skin_data.hpp), so the pairs stay few.
  size_t dup_a = in.size(), dup_b = in.size();
  for (size_t a = 0; a < in.size(); ++a) {
    if (in[a].weight == 0) continue;
    for (size_t b = a + 1; b < in.size(); ++b)
      if (in[b].weight != 0 && in[b].joint == in[a].joint &&
          (dup_a == in.size() || std::abs(in[a].weight + in[b].weight) > std::abs(in[dup_a].weight + in[dup_b].weight)))
        dup_a = a, dup_b = b;
  }
  if (dup_a < in.size()) {
    const double both = in[dup_a].weight + in[dup_b].weight;
    out["duplicate-joint"].add(std::abs(both), example(in[dup_a].joint, both), [&] {
      return "joint " + std::to_string(in[dup_a].joint) + " appears twice (weights " + number(in[dup_a].weight) + " and " +
             number(in[dup_b].weight) + ")" + at();
    });
  }
  // Beyond every skin that draws the mesh, or beyond the smaller ones only: the larger skin needs the
  // latter, so it is a warning and --fix keeps it.
  const Influence* beyond = nullptr;
  const Influence* beyond_some = nullptr;
  for (const Influence& i : in) {
    if (range.most == 0 || i.joint < range.fewest) continue;
    const Influence*& worst = i.joint >= range.most ? beyond : beyond_some;
    if (!worst || std::abs(i.weight) > std::abs(worst->weight)) worst = &i;
  }
  if (beyond)
    out["joint-out-of-range"].add(std::abs(beyond->weight), example(beyond->joint, double(beyond->joint)), [&] {
      return "joint index " + std::to_string(beyond->joint) + " (weight " + number(beyond->weight) + "), but the " +
             (range.fewest == range.most ? "skin has " : "largest skin that draws it has ") +
             std::to_string(range.most) + " joints" + at();
    });
  if (beyond_some)
    out["joint-beyond-smaller-skin"].add(
        std::abs(beyond_some->weight), example(beyond_some->joint, double(beyond_some->joint)), [&] {
          return "joint index " + std::to_string(beyond_some->joint) + " (weight " + number(beyond_some->weight) +
                 ") fits skin " + std::to_string(range.largest) + " (" + std::to_string(range.most) +
                 " joints) but not skin " + std::to_string(range.smallest) + " (" + std::to_string(range.fewest) +
                 " joints), which also draws it," + at();
        });
}

// Marks the joints of each skin that deform mesh primitives [first, last) (one mesh: the same skins) with
// weight on some vertex. Per mesh, the distinct joint indices with weight, then per skin those below its
// joint count: O(vertices + skins × min(joints, distinct indices)), where marking per vertex and skin
// would be vertices × skins.
void mark_used_joints(const std::vector<gltf::SkinnedPrimitive>& primitives, size_t first, size_t last,
                      std::vector<std::vector<bool>>& used) {
  size_t most = 0;  // joints of the largest skin: no index at or beyond it is any skin's
  for (int s : primitives[first].skins) most = std::max(most, used[size_t(s)].size());
  std::vector<bool> weighted;
  std::vector<uint32_t> distinct;
  for (size_t k = first; k < last && most > 0; ++k)
    for (const gltf::InfluenceSet& set : primitives[k].sets)
      for (size_t i = 0; i < set.joints.size(); ++i) {
        const uint32_t j = set.joints[i];
        if (!(set.weights[i] > 0) || j >= most) continue;
        if (j >= weighted.size()) weighted.resize(size_t(j) + 1, false);
        if (!weighted[j]) weighted[j] = true, distinct.push_back(j);
      }
  for (int s : primitives[first].skins) {
    std::vector<bool>& mark = used[size_t(s)];
    if (mark.size() < distinct.size()) {
      for (size_t j = 0; j < mark.size() && j < weighted.size(); ++j) mark[j] = mark[j] || weighted[j];
    } else {
      for (uint32_t j : distinct)
        if (j < mark.size()) mark[j] = true;
    }
  }
}

}  // namespace

void check_influences(const gltf::SkinData& data, const LintOptions& options, Findings& out) {
  const Asset& asset = data.structure;
  std::vector<std::vector<bool>> used(asset.skins.size());
  std::vector<bool> skinned(asset.skins.size(), false);
  for (size_t s = 0; s < asset.skins.size(); ++s) used[s].assign(asset.skins[s].joints.size(), false);

  std::vector<Influence> in;
  size_t mesh_first = 0;  // the first primitive of the current mesh (primitives come in mesh order)
  for (size_t k = 0; k < data.primitives.size(); ++k) {
    const gltf::SkinnedPrimitive& p = data.primitives[k];
    const JointRange range = joint_range(p, asset);
    for (int s : p.skins) skinned[size_t(s)] = true;
    for (size_t v = 0; v < p.vertices; ++v) {
      if (v % 65536 == 0) check_cancelled(options.cancel);
      in.clear();
      for (const gltf::InfluenceSet& set : p.sets) {
        const double scale = normalized_max(set.weights_component);
        for (size_t i = 0; i < 4; ++i)
          in.push_back({set.joints[4 * v + i], set.weights[4 * v + i], scale > 0 ? 0.5 / scale : 0.0});
      }
      check_vertex(p, v, in, range, options, out);
    }
    if (k + 1 == data.primitives.size() || data.primitives[k + 1].mesh != p.mesh) {
      mark_used_joints(data.primitives, mesh_first, k + 1, used);
      mesh_first = k + 1;
    }
  }

  // A skin no primitive uses is not linted for unused joints: nothing is deformed by it at all.
  for (size_t s = 0; s < asset.skins.size(); ++s) {
    if (!skinned[s]) continue;
    for (size_t j = 0; j < used[s].size(); ++j) {
      if (used[s][j]) continue;
      const int node = asset.skins[s].joints[j];
      LintExample e;
      e.where = "skin " + std::to_string(s);
      e.joint = static_cast<long long>(j);
      e.value = node;
      out["unused-joint"].add(0, e, [&] {
        const std::string& name = asset.nodes[size_t(node)].name;
        return "joint " + std::to_string(j) + " (node " + std::to_string(node) +
               (name.empty() ? "" : " '" + name + "'") + ") of skin " + std::to_string(s) + " has weight on no vertex";
      });
    }
  }
}

}  // namespace dqskin::lint
