// `dqskin lint --fix`: what can be corrected in the data itself. Influences: per vertex, every set's
// (joint, weight) merged per joint, weights ≤ 0 and joints beyond every skin that draws the mesh dropped
// (a joint that fits only the larger of two such skins is kept: that skin needs it), sorted by weight
// (descending; ties by joint), cut to max_influences (a vertex left without weight bound to its nearest
// joint) and renormalized in the original component type: normalized integers by the largest-remainder
// method, so that the stored integers sum exactly to 255 or 65535 (what the Khronos validator checks).
// Rotation keys: made unit (a key of length 0, no rotation at all, takes the nearest valid key of its
// channel, or the node's rest rotation), and each key negated when its dot product with the previous
// (already fixed) key is negative, CUBICSPLINE tangents with it (q and −q are the same rotation, so the
// animation is unchanged for a runtime that takes the shortest path, and becomes right for one that does
// not). A skin's `skeleton` that is not a common root of its joints is removed (the property is optional).
// Of channels of one animation that share a target (§3.11), the first is kept and the others removed.
#include "dqskin/lint.hpp"

#include "../load/fixed_glb.hpp"
#include "../load/skin_data.hpp"
#include "lint_checks.hpp"
#include "nearest_point.hpp"
#include "node_tree.hpp"
#include "dqskin/atomic_file.hpp"
#include "../base/byte_size.hpp"
#include "dqskin/error.hpp"
#include "dqskin/job.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <optional>

namespace dqskin {
namespace {

struct Influence {
  uint32_t joint;
  double weight;
};

// Largest-remainder rounding of weights that sum to 1 onto integers summing to exactly `scale`.
std::vector<double> round_to_sum(const std::vector<double>& w, double scale) {
  std::vector<double> floor(w.size()), remainder(w.size());
  double total = 0;
  for (size_t i = 0; i < w.size(); ++i) {
    floor[i] = std::floor(w[i] * scale);
    remainder[i] = w[i] * scale - floor[i];
    total += floor[i];
  }
  std::vector<size_t> order(w.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return remainder[a] > remainder[b]; });
  for (size_t k = 0; k < order.size() && total < scale; ++k, total += 1) floor[order[k]] += 1;
  for (double& f : floor) f /= scale;
  return floor;
}

// The joint nearest to a vertex in bind space (a joint's bind position is inverse(inverseBind) · origin),
// among the first `count` joints of `skin` (the mesh's first skin, up to as many joints as every skin that
// draws the mesh has, so that the index fits each). The tree is made when a vertex first needs it, and
// kept for the next primitives with the same skins.
class NearestJoints {
public:
  NearestJoints(const Asset& asset, int skin, size_t count) : asset_(asset), skin_(skin), count_(count) {}

  uint32_t operator()(const Vec3<double>& position) {
    if (!tree_) {
      std::vector<Vec3<double>> bind_positions;
      const std::vector<Mat4<double>>& ibms = asset_.skins[size_t(skin_)].inverse_bind;
      for (size_t j = 0; j < ibms.size() && j < count_; ++j)
        bind_positions.push_back(Vec3<double>(glm::inverse(ibms[j])[3]));
      tree_.emplace(bind_positions);
    }
    // A mesh without positions of its own (an accessor without a bufferView) has every vertex at one place.
    if (!last_ || *last_ != position) last_ = position, answer_ = uint32_t(tree_->nearest(position));
    return answer_;
  }

  bool fits(int skin, size_t count) const { return skin == skin_ && count == count_; }

private:
  const Asset& asset_;
  int skin_;
  size_t count_;
  std::optional<lint::NearestPoint> tree_;
  std::optional<Vec3<double>> last_;
  uint32_t answer_ = 0;
};

// The primitive's influences in fixed form, or nothing when they are already in it. An influence is
// dropped when its joint is beyond every skin that draws the mesh; one that fits the larger skins only is
// kept (they need it; lint warns, joint-beyond-smaller-skin).
std::optional<gltf::InfluenceEdit> fix_influences(const gltf::SkinnedPrimitive& p, const Asset& asset, size_t keep,
                                                  std::optional<NearestJoints>& nearest_joint) {
  const lint::JointRange range = lint::joint_range(p, asset);
  const size_t limit = range.most;
  // Joints a vertex without weight may be bound to: the first skin's, up to what every skin has.
  const int bind_skin = p.skins.empty() ? -1 : p.skins.front();
  const size_t bind_joints =
      bind_skin < 0 ? 0 : std::min(asset.skins[size_t(bind_skin)].inverse_bind.size(), range.fewest);
  if (bind_joints > 0 && !(nearest_joint && nearest_joint->fits(bind_skin, bind_joints)))
    nearest_joint.emplace(asset, bind_skin, bind_joints);
  const int weights_component = p.sets.front().weights_component;
  const double scale = lint::normalized_max(weights_component);
  std::vector<std::vector<Influence>> fixed(p.vertices);
  size_t most = 1;
  uint32_t largest_joint = 0;
  for (size_t v = 0; v < p.vertices; ++v) {
    std::vector<Influence>& in = fixed[v];
    for (const gltf::InfluenceSet& set : p.sets)
      for (size_t k = 0; k < 4; ++k) {
        const uint32_t j = set.joints[4 * v + k];
        const double w = set.weights[4 * v + k];
        if (!(w > 0) || (limit > 0 && j >= limit)) continue;
        auto same = std::find_if(in.begin(), in.end(), [&](const Influence& i) { return i.joint == j; });
        if (same != in.end())
          same->weight += w;
        else
          in.push_back({j, w});
      }
    std::stable_sort(in.begin(), in.end(), [](const Influence& a, const Influence& b) {
      return a.weight != b.weight ? a.weight > b.weight : a.joint < b.joint;
    });
    if (in.size() > keep) in.resize(keep);
    // A vertex without weight would stay where it was bound whatever the skeleton does: it is given to the
    // joint nearest to it in bind space.
    if (in.empty() && bind_joints > 0) in.push_back({(*nearest_joint)(Vec3<double>(p.positions[v])), 1.0});
    double sum = 0;
    for (const Influence& i : in) sum += i.weight;
    if (sum > 0) {
      std::vector<double> w(in.size());
      for (size_t i = 0; i < in.size(); ++i) w[i] = in[i].weight / sum;
      if (scale > 0) w = round_to_sum(w, scale);
      for (size_t i = 0; i < in.size(); ++i) in[i].weight = scale > 0 ? w[i] : double(float(w[i]));
    }
    // A weight that rounds to 0 is dropped: the Khronos validator wants joint 0 beside a zero weight.
    in.erase(std::remove_if(in.begin(), in.end(), [](const Influence& i) { return i.weight == 0; }), in.end());
    most = std::max(most, in.size());
    for (const Influence& i : in) largest_joint = std::max(largest_joint, i.joint);
  }

  gltf::InfluenceEdit e;
  e.mesh = p.mesh;
  e.primitive = p.primitive;
  e.vertices = p.vertices;
  e.sets = (most + 3) / 4;
  e.weights_component = weights_component;
  e.joints_component = largest_joint > 255 ? gltf::kComponentUnsignedShort : gltf::kComponentUnsignedByte;
  for (const gltf::InfluenceSet& set : p.sets)
    if (set.joints_component == gltf::kComponentUnsignedShort) e.joints_component = gltf::kComponentUnsignedShort;
  e.joints.assign(p.vertices * e.sets * 4, 0);
  e.weights.assign(p.vertices * e.sets * 4, 0.0);
  for (size_t v = 0; v < p.vertices; ++v)
    for (size_t i = 0; i < fixed[v].size(); ++i) {
      e.joints[v * e.sets * 4 + i] = fixed[v][i].joint;
      e.weights[v * e.sets * 4 + i] = fixed[v][i].weight;
    }

  bool same = e.sets == p.sets.size();
  for (size_t s = 0; same && s < p.sets.size(); ++s)
    same = p.sets[s].weights_component == e.weights_component && p.sets[s].joints_component == e.joints_component;
  for (size_t v = 0; same && v < p.vertices; ++v)
    for (size_t s = 0; same && s < e.sets; ++s)
      for (size_t k = 0; same && k < 4; ++k) {
        const size_t i = (v * e.sets + s) * 4 + k;
        same = float(p.sets[s].weights[4 * v + k]) == float(e.weights[i]) && p.sets[s].joints[4 * v + k] == e.joints[i];
      }
  if (same) return std::nullopt;
  return e;
}

// A rotation channel's keys made unit and hemisphere-consistent. A key of length 0 is no rotation and
// cannot be normalized: it takes the nearest key of the channel that can (nearest in time, the earlier of
// two equally near), or the node's rest rotation when no key of the channel can; a CUBICSPLINE key so
// replaced gets zero tangents (the curve rests on it).
std::optional<gltf::KeyEdit> fix_rotation(const gltf::RotationSource& source, const Asset& asset) {
  const Channel& ch = asset.clips[source.clip].channels[source.channel];
  const bool cubic = ch.interpolation == Interpolation::kCubicSpline;
  const size_t stride = cubic ? 12 : 4, offset = cubic ? 4 : 0;
  const double scale = lint::normalized_max(source.output_component);
  // What the type can hold: a length error below it is rounding, not something to fix.
  const double representable = scale > 0 ? 1 / scale : 1e-6;
  gltf::KeyEdit e;
  e.animation = source.animation;
  e.sampler = source.sampler;
  e.component = source.output_component;
  e.values = ch.values;
  bool changed = false;
  auto dot = [](const float* a, const float* b) {
    double d = 0;
    for (int i = 0; i < 4; ++i) d += double(a[i]) * double(b[i]);
    return d;
  };
  const size_t keys = ch.times.size();
  std::vector<bool> zero(keys, false);
  for (size_t k = 0; k < keys; ++k) {
    float* key = &e.values[k * stride];
    float* q = key + offset;
    const double length = std::sqrt(dot(q, q));
    zero[k] = !(length > 0);
    if (length > 0 && std::abs(length - 1) > representable) {
      for (size_t i = 0; i < stride; ++i) key[i] = float(double(key[i]) / length);  // tangents scale with their key
      changed = true;
    }
  }
  // The nearest normalizable key before and after each key, in two linear passes.
  constexpr size_t kNone = SIZE_MAX;
  std::vector<size_t> before(keys, kNone);
  for (size_t k = 0, last = kNone; k < keys; ++k) {
    before[k] = last;
    if (!zero[k]) last = k;
  }
  const Quat<double>& rest = asset.nodes[size_t(ch.node)].local.rotation;
  const float rest_xyzw[4] = {float(rest.x), float(rest.y), float(rest.z), float(rest.w)};
  for (size_t k = keys, after = kNone; k-- > 0;) {
    if (!zero[k]) {
      after = k;
      continue;
    }
    const size_t b = before[k];
    const bool take_before =
        b != kNone &&
        (after == kNone ||
         double(ch.times[k]) - double(ch.times[b]) <= double(ch.times[after]) - double(ch.times[k]));
    const float* from = take_before ? &e.values[b * stride + offset]
                        : after != kNone ? &e.values[after * stride + offset]
                                         : rest_xyzw;
    float* key = &e.values[k * stride];
    std::fill(key, key + stride, 0.0f);
    std::copy(from, from + 4, key + offset);
    changed = true;
  }
  const float* previous = nullptr;
  for (size_t k = 0; k < keys; ++k) {
    float* key = &e.values[k * stride];
    float* q = key + offset;
    // STEP keys are never interpolated, so their hemispheres do not matter (and the check reports none).
    if (previous && ch.interpolation != Interpolation::kStep && dot(previous, q) < 0) {
      for (size_t i = 0; i < stride; ++i) key[i] = -key[i];
      changed = true;
    }
    previous = q;
  }
  if (!changed) return std::nullopt;
  return e;
}

// Flushes the written file `temporary` to disk. Throws OutputError naming `output`.
void sync_to_disk(const std::string& temporary, const std::string& output) {
  const int fd = ::open(temporary.c_str(), O_RDONLY | O_CLOEXEC);
  const bool synced = fd >= 0 && ::fsync(fd) == 0;
  const int error = errno;
  if (fd >= 0) ::close(fd);
  if (!synced) throw OutputError(output + ": cannot write: " + std::strerror(error));
}

// About the most --fix holds, from the counts alone, so that a file whose rewrite cannot fit in
// --max-memory is refused at once with the figures (the ceiling, dqskin/memory_ceiling.hpp, would refuse
// it midway). While the influences are fixed: the data read (a position, and per set 4 joints and 4
// weights as double: 12 + 48 bytes a vertex), each vertex's merged influences (a vector: 24 bytes, and
// up to 4 a set of 16 bytes, as the allocator rounds a power of two, with its own 16) and the rewritten
// sets (4 slots a set, a 4-byte joint and an 8-byte weight). While the .glb is made: the rewritten sets,
// the file read again (its bytes and the model's buffers, then all of them in the BIN chunk and the
// .glb: 4 times its size) and the new accessors (up to 2-byte joints and 4-byte weights: in their view,
// in the BIN chunk and in the .glb).
struct FixMemory {
  uint64_t data = 0, influences = 0, sets = 0, glb = 0;
  uint64_t total() const { return std::max(data + influences + sets, sets + glb); }
};
FixMemory fix_memory(const gltf::SkinData& data, size_t keep, uint64_t file_bytes) {
  FixMemory m;
  const uint64_t out_sets = (std::min<uint64_t>(keep, kMaxInfluences) + 3) / 4;
  for (const gltf::SkinnedPrimitive& p : data.primitives) {
    const uint64_t v = p.vertices, slots = std::bit_ceil(std::max<uint64_t>(1, 4 * p.sets.size()));
    m.data += v * (12 + 48 * p.sets.size());
    m.influences += v * (24 + 16 + 16 * slots);
    m.sets += v * out_sets * 4 * (4 + 8);
    m.glb += 3 * v * out_sets * 4 * (2 + 4);
  }
  m.glb += 4 * file_bytes;
  return m;
}

// The edits that --fix makes to `input`: the data it reads for them is freed on return, before the .glb
// is made. Throws InputError for a file it cannot rewrite, or whose rewrite would take more than
// --max-memory.
gltf::FileEdits plan_edits(const std::string& input, const LintOptions& options) {
  const gltf::SkinData data = gltf::read_skin_data(input, options.load);
  if (!data.rewritable) throw InputError(data.why_not);
  std::error_code no_size;
  const uintmax_t file_bytes = std::filesystem::file_size(input, no_size);
  const FixMemory need = fix_memory(data, size_t(options.max_influences), no_size ? 0 : uint64_t(file_bytes));
  if (need.total() > options.load.max_memory) {
    size_t vertices = 0;
    for (const gltf::SkinnedPrimitive& p : data.primitives) vertices += p.vertices;
    throw InputError("rewriting the influences of " + std::to_string(vertices) + " vertices needs about " +
                     byte_size(need.total()) + " (" + byte_size(need.data) + " of data read, " +
                     byte_size(need.influences + need.sets) + " while they are fixed, " + byte_size(need.glb) +
                     " while the .glb is made), more than --max-memory " + byte_size(options.load.max_memory));
  }
  check_cancelled(options.cancel);
  gltf::FileEdits edits;
  std::optional<NearestJoints> nearest_joint;
  for (const gltf::SkinnedPrimitive& p : data.primitives) {
    if (auto e = fix_influences(p, data.structure, size_t(options.max_influences), nearest_joint))
      edits.influences.push_back(std::move(*e));
    check_cancelled(options.cancel);
  }
  for (const gltf::RotationSource& r : data.rotations)
    if (auto e = fix_rotation(r, data.structure)) edits.keys.push_back(std::move(*e));
  const Asset& a = data.structure;
  const lint::NodeTree tree(a.nodes);
  for (size_t s = 0; s < a.skins.size(); ++s) {
    const Skin& skin = a.skins[s];
    if (skin.skeleton >= 0 && !std::all_of(skin.joints.begin(), skin.joints.end(),
                                           [&](int joint) { return tree.is_ancestor_or_self(skin.skeleton, joint); }))
      edits.drop_skeleton.push_back(s);
  }
  for (const gltf::DuplicateChannel& d : data.duplicate_channels) edits.drop_channels.push_back({d.animation, d.second});
  return edits;
}

}  // namespace

LintFixSummary lint_fix(const std::string& input, const std::string& output, const LintOptions& options) {
  if (options.max_influences < 1 || options.max_influences > kMaxInfluences)
    throw InputError("--max-influences must be from 1 to " + std::to_string(kMaxInfluences) + " for --fix");
  const gltf::FileEdits edits = plan_edits(input, options);
  check_cancelled(options.cancel);
  const std::string glb = gltf::fixed_glb(input, options.load, edits);
  check_cancelled(options.cancel);
  AtomicFile file(output);
  file.write(glb);
  // On disk before the last look at the flag, so that a stop while the bytes are flushed (the longest
  // part of writing) leaves nothing; commit() then syncs a clean file and renames it, at once.
  sync_to_disk(file.hand_over(), output);
  check_cancelled(options.cancel);
  file.commit(Overwrite::kReplace);
  return {edits.influences.size(), edits.keys.size(), edits.drop_skeleton.size(), edits.drop_channels.size()};
}

}  // namespace dqskin
