// dqskin merge: the shards of a job into the manifest the unsharded job writes. Every shard plans the whole
// job and records the same inputs, animations and settings; what differs is its share: its outputs and,
// per animation, the figures of the whole-animation files it wrote (decode_check, morph). So the merge is
// one shard's manifest with the shared part checked against all others, the outputs' union (sorted by
// path as the bake sorts them) and each animation's figures from the shard that baked it.
#include "dqskin/verify.hpp"

#include "../job/job_manifest.hpp"
#include "dqskin/error.hpp"
#include "dqskin/job.hpp"
#include "folder_check.hpp"
#include "free_unbounded.hpp"
#include "manifest_swap.hpp"
#include "piece_assembly.hpp"

#include <algorithm>
#include <iterator>
#include <map>
#include <set>
#include <string_view>
#include <utility>

namespace dqskin {
namespace {

using namespace verify_detail;
using nlohmann::json;
namespace fs = std::filesystem;

// Per animation, what only the shard that wrote its whole-animation files knows.
// (render: the mode-diff scale, which only shards that drew frames of the animation record).
// A texture cut into slices: each slice's figures as a share, which the merge adds up (piece_assembly.hpp).
constexpr const char* kShardOwnKeys[] = {"decode_check", "decode_check_share", "morph", "mode_diff_max_distance"};

const json* animation(const json& manifest, size_t input, size_t clip) {
  const json& inputs = manifest["inputs"];
  if (input >= inputs.size() || !inputs[input].contains("animations")) return nullptr;
  const json& clips = inputs[input]["animations"];
  return clips.is_array() && clip < clips.size() && clips[clip].is_object() ? &clips[clip] : nullptr;
}

json* animation(json& manifest, size_t input, size_t clip) {
  return const_cast<json*>(animation(std::as_const(manifest), input, clip));
}

// Where a value lies in a manifest, as far as the shard's own share is concerned: the manifest itself
// (its shard and outputs are the shard's), and each input's animations (their kShardOwnKeys are).
enum class Level { kManifest, kInputs, kInput, kClips, kClip, kOther };

Level member_level(Level object, std::string_view key) {
  if (object == Level::kManifest && key == "inputs") return Level::kInputs;
  if (object == Level::kInput && key == "animations") return Level::kClips;
  return Level::kOther;
}

Level element_level(Level array) {
  return array == Level::kInputs ? Level::kInput : array == Level::kClips ? Level::kClip : Level::kOther;
}

// Whether member `key` of an object at `level` is the shard's own share, which shards do not agree on.
bool shard_own(Level object, std::string_view key) {
  if (object == Level::kManifest) return key == "shard" || key == "outputs" || key == "pieces";
  return object == Level::kClip && std::find(std::begin(kShardOwnKeys), std::end(kShardOwnKeys), key) != std::end(kShardOwnKeys);
}

// `value` (at `level`) without the shards' own shares in it.
void remove_shard_own(json& value, Level level) {
  if (value.is_object()) {
    for (auto it = value.begin(); it != value.end();) {
      if (shard_own(level, it.key())) {
        it = value.erase(it);
      } else {
        remove_shard_own(it.value(), member_level(level, it.key()));
        ++it;
      }
    }
  } else if (value.is_array()) {
    for (json& element : value) remove_shard_own(element, element_level(level));
  }
}

// `value` (at `level`) as a message quotes it: what all shards must agree on, on one line.
std::string shared_text(const json& value, Level level) {
  json copy = value;
  const FreedUnbounded<json> free_copy(copy);
  remove_shard_own(copy, level);
  return copy.dump(-1, ' ', false, json::error_handler_t::replace);
}

// Where `a` and `b` (at `level`) first differ, leaving out the shards' own shares, as "key.key[i]", with
// both values; empty when equal. Reads both in place: a copy of each shard's manifest without its share
// would copy its outputs first.
std::string first_difference(const json& a, const json& b, Level level, const std::string& at, std::string& a_value,
                             std::string& b_value) {
  if (a.type() == b.type() && a.is_object()) {
    std::set<std::string> keys;
    for (const auto& [k, v] : a.items())
      if (!shard_own(level, k)) keys.insert(k);
    for (const auto& [k, v] : b.items())
      if (!shard_own(level, k)) keys.insert(k);
    for (const std::string& k : keys) {
      const std::string here = at.empty() ? k : at + "." + k;
      if (!a.contains(k) || !b.contains(k)) {
        a_value = a.contains(k) ? shared_text(a[k], member_level(level, k)) : "absent";
        b_value = b.contains(k) ? shared_text(b[k], member_level(level, k)) : "absent";
        return here;
      }
      if (std::string d = first_difference(a[k], b[k], member_level(level, k), here, a_value, b_value); !d.empty())
        return d;
    }
    return {};
  }
  if (a.type() == b.type() && a.is_array() && a.size() == b.size()) {
    for (size_t i = 0; i < a.size(); ++i)
      if (std::string d = first_difference(a[i], b[i], element_level(level), at + "[" + std::to_string(i) + "]", a_value, b_value);
          !d.empty())
        return d;
    return {};
  }
  if (a == b) return {};
  a_value = shared_text(a, level);
  b_value = shared_text(b, level);
  return at.empty() ? "the whole manifest" : at;
}

std::string shortened(std::string s) {
  constexpr size_t kLongest = 80;
  return s.size() <= kLongest ? s : s.substr(0, kLongest - 3) + "...";
}

// The shards of one job (sorted by index, all N present) merged into `merged` (the caller's, which frees
// it whatever --max-memory says), or a refusal naming the shard that differs.
void merge_job(const std::string& folder, const std::vector<const JobManifest*>& shards, json& merged,
               std::vector<std::string>& refusals) {
  const JobManifest& first = *shards.front();
  for (size_t s = 1; s < shards.size(); ++s) {
    std::string first_value, this_value;
    const std::string at = first_difference(first.json, shards[s]->json, Level::kManifest, "", first_value, this_value);
    if (at.empty()) continue;
    const bool failed_input = at.size() > 6 && at.substr(at.size() - 6) == ".error";
    refusals.push_back(problem_location(folder, {shards[s]->name, {}, {}}) + ": " +
                       (failed_input ? "an input failed otherwise in this shard (run again the shard where it failed)"
                                     : "run with other flags, inputs or deformer") +
                       " than in " + first.name + " (" + at + ": " + shortened(this_value) + " here, " +
                       shortened(first_value) + " there)");
  }
  if (!refusals.empty()) return;

  merged = json::object();
  for (const auto& [key, value] : first.json.items())
    if (!shard_own(Level::kManifest, key)) merged[key] = value;
  merged["shard"] = {{"index", 0}, {"count", 1}};

  // The outputs' union by path (the bake's order); of a path listed twice, the first shard's entry.
  std::vector<const json*> outputs;
  for (const JobManifest* shard : shards)
    for (const json& out : shard->json["outputs"]) outputs.push_back(&out);
  const auto path = [](const json* out) -> const std::string& { return (*out)["path"].get_ref<const std::string&>(); };
  std::stable_sort(outputs.begin(), outputs.end(), [&](const json* a, const json* b) { return path(a) < path(b); });
  outputs.erase(std::unique(outputs.begin(), outputs.end(), [&](const json* a, const json* b) { return path(a) == path(b); }),
                outputs.end());
  json& list = merged["outputs"] = json::array();
  list.get_ref<json::array_t&>().reserve(outputs.size());
  for (const json* out : outputs) list.push_back(*out);

  // Each animation's own figures from the shard that wrote its whole-animation files.
  for (size_t i = 0; i < merged["inputs"].size(); ++i)
    for (size_t c = 0; json* clip = animation(merged, i, c); ++c)
      for (const char* key : kShardOwnKeys) {
        clip->erase(key);
        for (const JobManifest* shard : shards)
          if (const json* own = animation(shard->json, i, c); own && own->contains(key)) {
            (*clip)[key] = (*own)[key];
            break;
          }
      }
}

}  // namespace

MergeReport merge_shards(const std::string& given_folder, unsigned threads, const std::atomic<bool>* cancel) {
  MergeReport report;
  const std::string folder = folder_name(given_folder);
  ManifestSet set = read_manifests(folder, cancel);
  std::map<std::string, std::vector<const JobManifest*>> jobs;  // base → its shard manifests, by index
  for (const JobManifest& m : set.manifests)
    if (m.sharded()) jobs[m.base].push_back(&m);
  if (jobs.empty()) {
    report.verify = verify_folder(folder, threads, cancel);
    if (report.verify.ok()) return report;  // merged already, or a job that was never sharded
    report.refusals.push_back(folder + ": no shard manifests (manifest.shard-I-of-N.json) to merge");
    return report;
  }

  // The folder against the shards; the whole manifest each merge replaces is not consulted, nor is it a
  // problem when that one cannot be read.
  std::vector<const JobManifest*> checked;
  for (const JobManifest& m : set.manifests)
    if (m.sharded() || !jobs.count(m.base)) checked.push_back(&m);
  std::erase_if(set.problems, [&](const FolderProblem& p) {
    return std::any_of(jobs.begin(), jobs.end(), [&](const auto& job) { return p.path == job.first + ".json"; });
  });
  report.verify = check_folder(folder, set, checked, threads, cancel);

  for (auto& [base, shards] : jobs) {
    std::set<size_t> counts;
    for (const JobManifest* s : shards) counts.insert(s->shard.count);
    if (counts.size() > 1) {
      std::string list;
      for (size_t n : counts) list += (list.empty() ? "" : ", ") + std::to_string(n);
      report.refusals.push_back(folder + ": shard manifests of " + base + ".json for " + list +
                                " shards: one job was sharded two ways (delete the stale ones, or bake into an empty folder)");
    }
    std::sort(shards.begin(), shards.end(), [](auto* a, auto* b) { return a->shard.index < b->shard.index; });
  }
  if (!report.ok()) return report;

  std::vector<std::pair<std::string, json>> merged;
  const FreedUnbounded<std::vector<std::pair<std::string, json>>> free_merged(merged);
  merged.reserve(jobs.size());
  for (const auto& [base, shards] : jobs) {
    check_cancelled(cancel);
    merged.emplace_back(base + ".json", json());
    merge_job(folder, shards, merged.back().second, report.refusals);
  }
  if (!report.refusals.empty()) return report;
  // Files written in pieces, whole (the pieces go once the merged manifest is in).
  std::vector<std::string> pieces;
  size_t job = 0;
  for (const auto& [base, shards] : jobs) {
    check_cancelled(cancel);
    for (std::string& p : assemble_pieces(folder, shards, merged[job++].second, report.refusals)) pieces.push_back(std::move(p));
  }
  if (!report.refusals.empty()) return report;

  // All that the report says is made before the folder changes, so that nothing fails after it has.
  std::vector<ManifestText> written;
  std::vector<std::string> replaced;
  for (const auto& [name, manifest] : merged) {
    check_cancelled(cancel);
    written.push_back({name, job_manifest::text(manifest)});
    for (const json& in : manifest["inputs"])
      if (in.contains("error") && in["path"].is_string() && in["error"].is_string())
        report.failed_inputs.emplace_back(in["path"].get<std::string>(), in["error"].get<std::string>());
  }
  for (const auto& [base, shards] : jobs) {
    for (const JobManifest* s : shards) replaced.push_back(s->name);
    report.merged.push_back({base + ".json", shards.size()});
  }
  swap_in_manifests(folder, written, replaced, cancel);
  for (const std::string& piece : pieces) {
    std::error_code ignored;  // a piece left behind is only untidy: no manifest lists it
    fs::remove(folder + "/" + piece, ignored);
  }
  for (const auto& [name, manifest] : merged) job_manifest::clear_leftovers(folder, name, manifest);
  return report;
}

}  // namespace dqskin
