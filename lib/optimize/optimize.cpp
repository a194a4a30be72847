// `dqskin optimize` (dqskin/optimize.hpp): per clip, a search for the largest per-channel budget whose
// reduced channels keep the surface within the error budget, then the file written and measured again as
// read back (docs/DESIGN.md §3.12).
#include "dqskin/optimize.hpp"

#include "channel_reduction.hpp"
#include "levers.hpp"
#include "shared_grid.hpp"
#include "surface_error.hpp"
#include "../asset/source_document.hpp"
#include "../load/animation_glb.hpp"

#include "dqskin/atomic_file.hpp"
#include "dqskin/error.hpp"
#include "dqskin/job.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <map>
#include <memory>

namespace dqskin {
namespace {

using nlohmann::json;
using optimize_detail::ReducedChannel;

// The search accepts a candidate whose fast-deformer error is within this share of the budget: the
// written file is measured again by the double-precision reference, whose figures differ from the float
// deformer's by float rounding.
constexpr double kSearchMargin = 0.98;

// Where an Asset channel comes from in the file: its animation's channel and sampler, and the output's
// component type. Channels that cannot be rewritten on their own (a sampler shared with another channel,
// a KHR_animation_pointer target) have none.
struct ChannelSource {
  bool rewritable = false;
  size_t channel = 0, sampler = 0;
  int component = 5126;
};

// The file channels of animation `a` matched to clip channels by node and path. A clip with pointer or
// duplicate channels is matched not at all (`why` says so): its channels are kept as they are.
std::vector<ChannelSource> match_channels(const json& doc, size_t a, const Clip& clip, std::string& why) {
  std::vector<ChannelSource> sources(clip.channels.size());
  if (!doc.contains("animations") || a >= doc["animations"].size()) {
    why = "its animation is not in the document";
    return sources;
  }
  const json& animation = doc["animations"][a];
  const json& channels = animation.value("channels", json::array());
  const json& accessors = doc.value("accessors", json::array());
  std::map<size_t, int> sampler_users;
  for (const json& c : channels) ++sampler_users[c.value("sampler", size_t(0))];
  std::map<std::pair<int, std::string>, size_t> by_target;
  for (size_t c = 0; c < channels.size(); ++c) {
    const json& target = channels[c].value("target", json::object());
    if (!target.contains("node") || target.value("path", std::string()) == "pointer") {
      why = "it has KHR_animation_pointer channels, which are kept as they are";
      return std::vector<ChannelSource>(clip.channels.size());
    }
    if (!by_target.emplace(std::make_pair(target["node"].get<int>(), target.value("path", std::string())), c).second) {
      why = "it has two channels with one target, which are kept as they are";
      return std::vector<ChannelSource>(clip.channels.size());
    }
  }
  for (size_t i = 0; i < clip.channels.size(); ++i) {
    const Channel& ch = clip.channels[i];
    const auto it = by_target.find({ch.node, target_path_name(ch.path)});
    if (it == by_target.end()) continue;
    const size_t s = channels[it->second].value("sampler", size_t(0));
    if (sampler_users[s] != 1) continue;
    const json& sampler = animation["samplers"][s];
    const size_t output = sampler.value("output", size_t(0));
    sources[i] = {true, it->second, s, output < accessors.size() ? accessors[output].value("componentType", 5126) : 5126};
  }
  return sources;
}

// The node's rest value of a channel's path as floats (null for weights: a weights channel is never dropped).
const float* rest_value(const Asset& asset, const Channel& ch, float (&out)[4]) {
  if (ch.node < 0 || ch.path == TargetPath::kWeights) return nullptr;
  const LocalTransform& t = asset.nodes[size_t(ch.node)].local;
  if (t.has_matrix) return nullptr;
  switch (ch.path) {
    case TargetPath::kTranslation: out[0] = float(t.translation.x), out[1] = float(t.translation.y), out[2] = float(t.translation.z); break;
    case TargetPath::kScale: out[0] = float(t.scale.x), out[1] = float(t.scale.y), out[2] = float(t.scale.z); break;
    case TargetPath::kRotation:
      out[0] = float(t.rotation.x), out[1] = float(t.rotation.y), out[2] = float(t.rotation.z), out[3] = float(t.rotation.w);
      break;
    case TargetPath::kWeights: return nullptr;
  }
  return out;
}

// How many of the clip's rewritable channels one vertex can feel at most: the largest dependency set's
// count (docs/DESIGN.md §3.12: the budget is shared by the channels of one chain).
size_t channels_on_a_chain(const optimize_detail::Levers& levers, const Clip& clip,
                           const std::vector<ChannelSource>& sources) {
  std::map<int, size_t> per_node;  // node → channels; -1 - node for its weights
  for (size_t i = 0; i < clip.channels.size(); ++i) {
    if (!sources[i].rewritable) continue;
    const Channel& ch = clip.channels[i];
    ++per_node[ch.path == TargetPath::kWeights ? -1 - ch.node : ch.node];
  }
  size_t most = 0;
  for (const std::vector<int>& set : levers.dependency_sets) {
    size_t n = 0;
    for (int node : set) {
      const auto it = per_node.find(node);
      if (it != per_node.end()) n += it->second;
    }
    most = std::max(most, n);
  }
  return most;
}

struct Candidate {
  Clip clip;
  std::vector<ReducedChannel> reduced;  // per input channel
  std::vector<int> stored;              // per input channel: the normalized integer type it is stored as, or 0
  bool changed = false;
};

// A normalized integer component type of glTF 2.0 §3.11 ("Animation samplers" allows them for rotations
// and weights): a value v is stored as c = round(v · scale) and read back as max(c / scale, −1), as the
// loader decodes it, so that the search measures what the file will hold.
struct Normalized {
  int component;
  double scale;
  double lowest;  // the smallest value it holds
};
constexpr Normalized kByte{5120, 127, -1}, kUnsignedByte{5121, 255, 0}, kShort{5122, 32767, -1},
    kUnsignedShort{5123, 65535, 0};

float stored_value(float v, const Normalized& type) {
  const double c = std::round(std::clamp(double(v), type.lowest, 1.0) * type.scale);
  return float(std::max(c / type.scale, -1.0));
}

void store_as(Channel& channel, const Normalized& type) {
  for (float& v : channel.values) v = stored_value(v, type);
}

// The smallest normalized type whose rounding keeps a weights channel within `budget` (through its levers),
// or null: 8 bits, else 16. Weights outside [−1, 1] stay floats (glTF leaves their range open).
const Normalized* weights_type(const Channel& channel, const optimize_detail::NodeLevers& levers, double budget) {
  if (channel.values.empty()) return nullptr;
  const auto [lo, hi] = std::minmax_element(channel.values.begin(), channel.values.end());
  if (*lo < -1 || *hi > 1) return nullptr;
  const bool negative = *lo < 0;
  const optimize_detail::ChannelError error(channel, levers);
  const size_t n = size_t(channel.components);
  for (const Normalized* type : {negative ? &kByte : &kUnsignedByte, negative ? &kShort : &kUnsignedShort}) {
    Channel rounded = channel;
    store_as(rounded, *type);
    double worst = 0;
    for (size_t k = 0; k < channel.times.size(); ++k)
      worst = std::max(worst, error(&channel.values[k * n], &rounded.values[k * n]));
    if (worst <= budget) return type;
  }
  return nullptr;
}

// The clip with every rewritable channel reduced under `channel_budget`, its end kept where it was.
Candidate reduce_clip(const Asset& asset, const Clip& clip, const std::vector<ChannelSource>& sources,
                      const optimize_detail::Levers& levers, double channel_budget, const OptimizeOptions& options) {
  Candidate c;
  c.clip = clip;
  c.clip.channels.clear();
  c.reduced.resize(clip.channels.size());
  c.stored.assign(clip.channels.size(), 0);
  std::vector<bool> moves(clip.channels.size(), false), on_grid(clip.channels.size(), false);
  std::vector<size_t> value_bytes(clip.channels.size(), 0);
  for (size_t i = 0; i < clip.channels.size(); ++i) {
    const Channel& ch = clip.channels[i];
    ReducedChannel& r = c.reduced[i];
    // A node's transform moves the vertices skinned to its subtree or drawn under it; its weights move its
    // mesh's morph targets (a skinned mesh's node moves nothing by its transform, but its weights do).
    const optimize_detail::NodeLevers* node = ch.node >= 0 ? &levers.nodes[size_t(ch.node)] : nullptr;
    moves[i] = node && (ch.path == TargetPath::kWeights ? !node->weights.empty() : node->moves_vertices);
    if (!sources[i].rewritable || !moves[i] || !options.remove_keys) {
      r.channel = ch;
      continue;
    }
    float rest[4] = {0, 0, 0, 0};
    r = optimize_detail::reduce_channel(ch, levers.nodes[size_t(ch.node)], channel_budget, rest_value(asset, ch, rest),
                                        {options.drop_channels, options.convert_interpolation}, options.threads);
    on_grid[i] = options.share_times && !r.dropped && ch.interpolation == Interpolation::kLinear &&
                 r.channel.interpolation == Interpolation::kLinear;
    const bool shorts = ch.path == TargetPath::kRotation && options.quantize_rotations && sources[i].component == 5126;
    value_bytes[i] = size_t(ch.components) * (shorts ? 2 : ch.path == TargetPath::kWeights ? 1 : 4);
  }
  optimize_detail::share_grid(clip, c.reduced, on_grid, value_bytes, levers, channel_budget);
  for (size_t i = 0; i < clip.channels.size(); ++i) {
    const Channel& ch = clip.channels[i];
    ReducedChannel& r = c.reduced[i];
    // Normalized integers for floats of LINEAR and STEP channels (CUBICSPLINE tangents may leave [−1, 1]).
    if (sources[i].rewritable && moves[i] && !r.dropped && sources[i].component == 5126 &&
        r.channel.interpolation != Interpolation::kCubicSpline) {
      const Normalized* type = nullptr;
      if (ch.path == TargetPath::kRotation && options.quantize_rotations) type = &kShort;
      if (ch.path == TargetPath::kWeights && options.quantize_weights)
        type = weights_type(r.channel, levers.nodes[size_t(ch.node)], channel_budget);
      if (type) {
        store_as(r.channel, *type);
        c.stored[i] = type->component;
      }
    }
    c.changed = c.changed || r.dropped || c.stored[i] != 0 || r.channel.times != ch.times ||
                r.channel.interpolation != ch.interpolation;
    if (!r.dropped) c.clip.channels.push_back(r.channel);
  }
  // A clip lasts until its last key (glTF time starts at 0): if every channel that reached the end lost its
  // last key, the first of them keeps its last value there (a repeat is exact: the value is held).
  double end = 0;
  for (const Channel& ch : c.clip.channels)
    if (!ch.times.empty()) end = std::max(end, double(ch.times.back()));
  if (end < clip.last_key) {
    bool extended = false;
    for (size_t i = 0; i < clip.channels.size() && !extended; ++i) {
      ReducedChannel& r = c.reduced[i];
      if (r.dropped || double(clip.channels[i].times.back()) < clip.last_key || r.channel.interpolation == Interpolation::kCubicSpline)
        continue;
      const size_t n = size_t(r.channel.components);
      r.channel.times.push_back(clip.channels[i].times.back());
      r.channel.values.insert(r.channel.values.end(), r.channel.values.end() - std::ptrdiff_t(n), r.channel.values.end());
      extended = true;
    }
    // Every channel that reached the end was dropped: the first comes back as its node's rest value held
    // from its first key to the end (within the budget, as the drop was).
    for (size_t i = 0; i < clip.channels.size() && !extended; ++i) {
      ReducedChannel& r = c.reduced[i];
      float rest[4] = {0, 0, 0, 0};
      const Channel& ch = clip.channels[i];
      if (!r.dropped || double(ch.times.back()) < clip.last_key || !rest_value(asset, ch, rest)) continue;
      r.dropped = false;
      r.channel = ch;
      r.channel.interpolation = Interpolation::kLinear;
      r.channel.times = {ch.times.front(), ch.times.back()};
      r.channel.values.assign(rest, rest + ch.components);
      r.channel.values.insert(r.channel.values.end(), rest, rest + ch.components);
      extended = true;
    }
    c.clip.channels.clear();
    for (const ReducedChannel& r : c.reduced)
      if (!r.dropped) c.clip.channels.push_back(r.channel);
  }
  return c;
}

size_t key_count(const Clip& clip) {
  size_t keys = 0;
  for (const Channel& ch : clip.channels) keys += ch.times.size();
  return keys;
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

uint64_t file_size_of(const std::string& path) {
  std::error_code error;
  const auto size = std::filesystem::file_size(path, error);
  return error ? 0 : uint64_t(size);
}

// The edits for the chosen candidates: a new sampler for every rewritable channel of a clip that changed,
// and the channels dropped.
gltf::AnimationEdits make_edits(const json& doc, const Asset& asset, const std::vector<Candidate>& chosen) {
  gltf::AnimationEdits edits;
  for (size_t a = 0; a < asset.clips.size(); ++a) {
    const Candidate& c = chosen[a];
    if (!c.changed) continue;  // its samplers stay as they are, bufferViews and all
    std::string ignored;
    const std::vector<ChannelSource> sources = match_channels(doc, a, asset.clips[a], ignored);
    for (size_t i = 0; i < c.reduced.size(); ++i) {
      const ReducedChannel& r = c.reduced[i];
      if (!sources[i].rewritable) continue;
      if (r.dropped) {
        edits.drop_channels.emplace_back(a, sources[i].channel);
        continue;
      }
      // Every sampler is written again, changed or not: exporters pack a clip's keys into shared
      // bufferViews, which only leave the file when no old accessor uses them any more.
      gltf::SamplerEdit e;
      e.animation = a;
      e.sampler = sources[i].sampler;
      e.times = r.channel.times;
      e.values = r.channel.values;
      e.components = r.channel.path == TargetPath::kWeights ? 1 : r.channel.components;
      e.component = c.stored[i] != 0 ? c.stored[i] : sources[i].component;
      e.interpolation = r.channel.interpolation == Interpolation::kStep          ? "STEP"
                        : r.channel.interpolation == Interpolation::kCubicSpline ? "CUBICSPLINE"
                                                                                   : "LINEAR";
      edits.samplers.push_back(std::move(e));
    }
  }
  // glTF 2.0 §5.9: an animation has at least one channel; the last of one that would lose them all stays.
  for (size_t a = 0; a < asset.clips.size(); ++a) {
    size_t dropped = 0, channels = doc["animations"][a]["channels"].size();
    for (const auto& d : edits.drop_channels) dropped += d.first == a;
    if (dropped == channels && channels > 0) {
      const auto last = std::find_if(edits.drop_channels.rbegin(), edits.drop_channels.rend(),
                                     [a](const auto& d) { return d.first == a; });
      edits.drop_channels.erase(std::next(last).base());
    }
  }

  return edits;
}

}  // namespace

OptimizeSummary optimize(const std::string& input, const std::string& output, const OptimizeOptions& options) {
  if (!(options.max_error_percent >= 0) && !(options.max_error >= 0 && std::isfinite(options.max_error)))
    throw InputError("--max-error must be a length of at least 0, not " + std::to_string(options.max_error));
  if (options.max_error_percent >= 0 && !std::isfinite(options.max_error_percent))
    throw InputError("--max-error must be a finite percentage");
  LoadOptions load = options.load;
  load.keep_source = true;
  const Asset asset = load_asset(input, load);
  if (asset.clips.empty()) throw InputError(input + ": has no animation to optimize");
  if (!asset.cannot_deform.empty()) throw InputError(input + ": " + asset.cannot_deform.front());
  check_cancelled(options.cancel);

  OptimizeSummary summary;
  summary.input = input;
  summary.output = output;
  summary.mode = options.mode;
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  if (instances.empty()) throw InputError(input + ": its scene draws no mesh, so no error can be measured");
  const optimize_detail::Levers levers = optimize_detail::compute_levers(asset, instances, options.mode);
  summary.diagonal = levers.diagonal;
  summary.budget = options.max_error_percent >= 0 ? options.max_error_percent / 100 * levers.diagonal : options.max_error;
  const double budget = summary.budget;
  const json& doc = asset.source->json;
  // Made now, so that an output that cannot be written fails before the search (removed on any failure).
  auto file = std::make_unique<AtomicFile>(output);

  std::vector<Candidate> chosen(asset.clips.size());
  for (size_t a = 0; a < asset.clips.size(); ++a) {
    const Clip& clip = asset.clips[a];
    std::string why;
    const std::vector<ChannelSource> sources = match_channels(doc, a, clip, why);
    if (!why.empty()) summary.notes.push_back("clip '" + clip.name + "' is kept as it is: " + why);
    const std::vector<double> times = optimize_detail::judged_times(clip);
    const size_t chain = std::max<size_t>(1, channels_on_a_chain(levers, clip, sources));
    // The largest factor k whose channel budget k × budget / chain keeps the surface within the budget:
    // k = 1 shares the budget exactly along the longest chain; the errors of a chain's channels seldom add
    // up, so larger factors are tried, up to all of it per channel (k = chain) and four times that, for
    // the levers' bounds are loose; then 5 geometric bisections. With quantized rotations first; when
    // their rounding alone is over the budget, again with floats. At most 13 measurements a pass.
    Candidate best;
    double best_k = 0;
    OptimizeOptions pass = options;
    for (int attempt = 0; attempt < 2 && best_k == 0; ++attempt, pass.quantize_rotations = pass.quantize_weights = false) {
      if (attempt == 1 && !options.quantize_rotations && !options.quantize_weights) break;
      // A failing candidate is known at its first chunk of times past the bound; the next one is looked at
      // first where the last one failed. Only pass or fail matters here, so the decisions are those of a
      // full measurement.
      double failed_at = -1;
      auto error_at = [&](double k, Candidate& out) {
        out = reduce_clip(asset, clip, sources, levers, k * budget / double(chain), pass);
        check_cancelled(options.cancel);
        if (!out.changed) return 0.0;
        const optimize_detail::SurfaceError e = optimize_detail::surface_error(
            asset, clip, asset, out.clip, instances, times, budget, options.mode, Backend::kFastCpu, options.threads,
            kSearchMargin * budget, failed_at);
        if (e.max > kSearchMargin * budget) failed_at = e.max_time;
        check_cancelled(options.cancel);
        return e.max;
      };
      Candidate trial;
      double k = 1;
      for (int halvings = 0; halvings <= 6; ++halvings, k /= 2)
        if (error_at(k, trial) <= kSearchMargin * budget) {
          best = std::move(trial);
          best_k = k;
          break;
        }
      if (best_k == 0) continue;
      double lo = best_k, hi = 4.0 * double(chain);
      if (error_at(hi, trial) <= kSearchMargin * budget) {
        best = std::move(trial), best_k = hi;
      } else {
        for (int step = 0; step < 5; ++step) {
          const double mid = std::sqrt(lo * hi);
          if (error_at(mid, trial) <= kSearchMargin * budget) best = std::move(trial), best_k = lo = mid;
          else hi = mid;
        }
      }
    }
    if (best_k == 0) summary.notes.push_back("clip '" + clip.name + "' is kept as it is: no reduction met the budget");
    chosen[a] = std::move(best);
    ClipOptimization c;
    c.name = clip.name;
    c.channels_before = clip.channels.size();
    c.keys_before = key_count(clip);
    c.judged_times = times.size();
    c.scale_factor = chosen[a].changed ? best_k : 0;
    summary.clips.push_back(c);
  }

  // Written and measured again on the file as read back, by the double-precision reference deformer. A
  // clip over the budget there (the search measured with the float deformer) is written as it was, and
  // the file again: at most one more pass, as an unchanged clip is exact.
  std::vector<optimize_detail::SurfaceError> errors(asset.clips.size());
  gltf::AnimationGlb written;
  for (int pass = 0;; ++pass) {
    const gltf::AnimationEdits edits = make_edits(doc, asset, chosen);
    check_cancelled(options.cancel);
    written = gltf::animation_glb(input, load, edits);
    if (pass > 0) file = std::make_unique<AtomicFile>(output);
    file->write(written.glb);
    const Asset out = load_asset(file->hand_over(), options.load);
    if (out.clips.size() != asset.clips.size()) throw OutputError(output + ": read back with a different clip count");
    bool over = false;
    for (size_t a = 0; a < asset.clips.size(); ++a) {
      ClipOptimization& c = summary.clips[a];
      c.channels_after = out.clips[a].channels.size();
      c.keys_after = key_count(out.clips[a]);
      errors[a] = optimize_detail::surface_error(asset, asset.clips[a], out, out.clips[a], instances,
                                                 optimize_detail::judged_times(asset.clips[a]), budget, options.mode,
                                                 Backend::kCpu, options.threads);
      check_cancelled(options.cancel);
      if (!(errors[a].max > budget)) continue;
      if (!chosen[a].changed || pass > 0)
        throw OutputError(output + ": clip '" + c.name + "' is off by " + number(errors[a].max) +
                          " as written, over the budget " + number(budget) + " (please report this file)");
      summary.notes.push_back("clip '" + c.name + "' is kept as it is: its reduction measured " +
                              number(errors[a].max) + " on the written file, over the budget " + number(budget));
      chosen[a].changed = false;
      c.scale_factor = 0;
      over = true;
    }
    if (!over) break;
  }
  if (!written.kept_unused.empty()) summary.notes.push_back("unused data is kept: " + written.kept_unused);
  for (size_t a = 0; a < asset.clips.size(); ++a) {
    ClipOptimization& c = summary.clips[a];
    const optimize_detail::SurfaceError& e = errors[a];
    c.max_error = e.max;
    c.p99_error = e.p99;
    c.max_error_time = e.max_time;
    c.max_error_joint = e.max > 0 ? optimize_detail::vertex_joint(asset, instances, e.max_instance, e.max_primitive, e.max_vertex) : "";
  }
  summary.animation_bytes_before = written.animation_bytes_before;
  summary.animation_bytes_after = written.animation_bytes_after;
  summary.file_bytes_before = file_size_of(input);
  summary.file_bytes_after = written.glb.size();
  if (std::none_of(chosen.begin(), chosen.end(), [](const Candidate& c) { return c.changed; }))
    summary.notes.push_back("no key or channel could go within the budget: the output's animation is the input's");
  check_cancelled(options.cancel);
  file->commit(Overwrite::kReplace);
  return summary;
}

}  // namespace dqskin
