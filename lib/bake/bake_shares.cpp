#include "bake_shares.hpp"

#include "vat_bake.hpp"

#include <algorithm>
#include <numeric>
#include <optional>

namespace dqskin::bake_detail {
namespace {

// Seconds per million vertex-frames of each format baked alone (BrainStem on the 2-core reference
// machine, docs/PERFORMANCE.md "Scale-out"); only their ratios matter. A checked texture costs most: VAT
// encoding (EXR compression) and the decode-back check, bone textures the check (every frame and midpoint
// skinned again in double precision).
constexpr double kGlb = 0.14, kPly = 0.10, kObj = 0.12, kMorph = 0.24;
constexpr double kVat = 1.0, kVatCheck = 0.46, kBones = 0.01, kBonesCheck = 0.59;

bool has(unsigned formats, BakeFormat f) { return formats & unsigned(f); }

struct ClipWork {
  ClipPlan* clip = nullptr;
  size_t first = 0;                   // the clip's first frame in the sequence of every clip's frames
  double per_frame = 0;               // a frame's per-frame files
  double slice_per_frame = 0;         // a frame's slice of the textures, when cut
  double head = 0, morph = 0;         // what goes whole: the textures when they cannot be cut; the morph animation
  std::optional<texture::VatEncoding> vat;  // a cut texture: where a slice may start
  bool sliced = false;
  size_t head_shard = 0, morph_shard = 0;
};

// The frame nearest to f at which a slice of `work`'s textures may start (the clip's first and last count).
size_t nearest_cut(const ClipWork& work, size_t f) {
  const size_t frames = work.clip->times.size();
  if (!work.vat) return f;
  for (size_t d = 0;; ++d) {
    if (f >= d && texture::slice_may_start(*work.vat, f - d)) return f - d;
    if (f + d >= frames) return frames;
    if (texture::slice_may_start(*work.vat, f + d)) return f + d;
  }
}

// Cuts every clip's frames, one after another, into runs whose costs (`cost` per frame) are in proportion
// to each shard's `room`: cuts[s] is the first frame after shard s's run. The frame whose middle passes
// the cost wanted ends a run; with `slices`, then the nearest frame a texture slice may start at.
std::vector<size_t> cut_runs(const std::vector<ClipWork>& work, double ClipWork::*cost, const std::vector<double>& room,
                             size_t total_frames, bool slices) {
  double all = 0;
  for (const ClipWork& w : work) all += w.*cost * double(w.clip->times.size());
  const double room_sum = std::accumulate(room.begin(), room.end(), 0.0);
  std::vector<size_t> cuts(room.size(), total_frames);
  double wanted = 0, walked = 0;  // walked: the cost of the frames before (c, f)
  size_t c = 0, f = 0;
  for (size_t s = 0; s + 1 < room.size(); ++s) {
    wanted += room_sum > 0 ? room[s] / room_sum * all : all * double(s + 1) / double(room.size()) - wanted;
    while (c < work.size() && walked + work[c].*cost / 2 < wanted) {
      walked += work[c].*cost;
      if (++f == work[c].clip->times.size()) ++c, f = 0;
    }
    const size_t cut = c == work.size() ? total_frames : work[c].first + (slices ? nearest_cut(work[c], f) : f);
    cuts[s] = std::max(cut, s > 0 ? cuts[s - 1] : 0);
  }
  return cuts;
}

}  // namespace

void deal_bake_shares(std::vector<InputPlan>& plans, const BakeOptions& options) {
  const Shard shard = options.plan.shard;
  if (shard.whole() || options.textures.combine_clips) return;
  const unsigned formats = options.formats;
  const TextureOptions& t = options.textures;
  std::vector<ClipWork> work;
  size_t total_frames = 0;
  for (InputPlan& input : plans) {
    if (!input.error.empty()) continue;
    double vertices = 0;  // millions
    for (const MeshInstance& inst : input.instances)
      for (const Primitive& p : input.asset->meshes[size_t(inst.mesh)].primitives) vertices += double(p.vertex_count()) / 1e6;
    const bool vat = has(formats, BakeFormat::kVat), bones = has(formats, BakeFormat::kBones) && !input.skins.empty();
    for (ClipPlan& clip : input.clips) {
      ClipWork w;
      w.clip = &clip;
      w.first = total_frames;
      const double frames = double(clip.times.size());
      total_frames += clip.times.size();
      w.per_frame = vertices * ((has(formats, BakeFormat::kGlb) ? kGlb : 0) + (has(formats, BakeFormat::kPly) ? kPly : 0) +
                                (has(formats, BakeFormat::kObj) ? kObj : 0));
      const double textures = vertices * ((vat ? kVat + (t.check ? kVatCheck : 0) : 0) + (bones ? kBones + (t.check ? kBonesCheck : 0) : 0));
      // Cut where every texture asked for can be: a VAT of EXR rows, bone textures whose --max-error is
      // not relative to the clip's size (a slice sees its own frames only).
      if (vat) w.vat = sliceable_vat(input, clip, t);
      w.sliced = (vat || bones) && clip.times.size() > 1 && (!vat || w.vat) && (!bones || !(t.max_error > 0 && t.max_error_relative));
      if (!w.sliced) w.vat.reset();
      if (w.sliced) w.slice_per_frame = textures;
      else w.head = textures * frames;
      if (has(formats, BakeFormat::kMorph)) w.morph = vertices * kMorph * frames;
      work.push_back(std::move(w));
    }
  }
  if (work.empty()) return;

  // What goes whole, largest first, each to the least loaded shard (the first of equals).
  std::vector<double> load(shard.count, 0.0);
  struct Whole {
    double cost;
    size_t clip;
    bool morph;
  };
  std::vector<Whole> wholes;
  for (size_t c = 0; c < work.size(); ++c) {
    if (!work[c].sliced) wholes.push_back({work[c].head, c, false});
    if (work[c].morph > 0) wholes.push_back({work[c].morph, c, true});
  }
  std::stable_sort(wholes.begin(), wholes.end(), [](const Whole& a, const Whole& b) { return a.cost > b.cost; });
  for (const Whole& w : wholes) {
    const size_t s = size_t(std::min_element(load.begin(), load.end()) - load.begin());
    load[s] += w.cost;
    (w.morph ? work[w.clip].morph_shard : work[w.clip].head_shard) = s;
  }

  // The frames in runs, twice: the textures' slices over the shards without whole work (which holds the
  // most memory: the morph animation keeps every frame), then the per-frame files over every shard, each
  // run costing what brings its shard to the mean.
  double texture_cost = 0, file_cost = 0;
  for (const ClipWork& w : work) {
    texture_cost += w.slice_per_frame * double(w.clip->times.size());
    file_cost += w.per_frame * double(w.clip->times.size());
  }
  const double mean = (texture_cost + file_cost + std::accumulate(load.begin(), load.end(), 0.0)) / double(shard.count);
  std::vector<double> room(shard.count, 0.0);
  const size_t free_shards = size_t(std::count(load.begin(), load.end(), 0.0));
  for (size_t s = 0; s < shard.count; ++s)
    if (free_shards == 0 || load[s] == 0) room[s] = 1;
  const std::vector<size_t> texture_cuts = cut_runs(work, &ClipWork::slice_per_frame, room, total_frames, true);
  const double texture_shards = double(std::count(room.begin(), room.end(), 1.0));
  for (size_t s = 0; s < shard.count; ++s) {
    if (room[s] > 0) load[s] += texture_cost / texture_shards;
    room[s] = std::max(0.0, mean - load[s]);
  }
  const std::vector<size_t> file_cuts = cut_runs(work, &ClipWork::per_frame, room, total_frames, false);
  auto run = [&](const std::vector<size_t>& cuts) {
    return std::pair(shard.index > 0 ? cuts[shard.index - 1] : 0, cuts[shard.index]);
  };
  const auto [begin, end] = run(file_cuts);
  const auto [texture_begin, texture_end] = run(texture_cuts);
  auto owner = [&](size_t g) { return size_t(std::upper_bound(texture_cuts.begin(), texture_cuts.end(), g) - texture_cuts.begin()); };

  for (ClipWork& w : work) {
    ClipPlan& clip = *w.clip;
    const size_t frames = clip.times.size();
    for (size_t k = 0; k < frames; ++k) clip.frame_mine[k] = w.first + k >= begin && w.first + k < end;
    clip.morph_mine = w.morph > 0 && w.morph_shard == shard.index;
    if (w.sliced) {
      // The clip's head is the shard with its first frame; each shard with frames of it has their slice.
      clip.clip_mine = owner(w.first) == shard.index;
      clip.texture_first = std::clamp(texture_begin, w.first, w.first + frames) - w.first;
      clip.texture_end = std::clamp(texture_end, w.first, w.first + frames) - w.first;
      if (clip.texture_first >= clip.texture_end) clip.texture_first = clip.texture_end = 0;
    } else {
      clip.clip_mine = w.head_shard == shard.index;
      clip.texture_first = 0;
      clip.texture_end = clip.clip_mine ? frames : 0;
    }
  }
}

}  // namespace dqskin::bake_detail
