// dqskin merge: the shards of a job into the manifest the unsharded job writes. Every shard plans the whole
// job and records the same inputs, animations and settings; what differs is its share: its outputs and,
// per animation, the figures of the whole-animation files it wrote (decode_check, morph). So the merge is
// one shard's manifest with the shared part checked against all others, the outputs' union (sorted by
// path as the bake sorts them) and each animation's figures from the shard that baked it.
#include "dqskin/verify.hpp"

#include "../job/job_manifest.hpp"
#include "dqskin/error.hpp"
#include "folder_check.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <utility>

namespace dqskin {
namespace {

using namespace verify_detail;
using nlohmann::json;
namespace fs = std::filesystem;

// Per animation, what only the shard that wrote its whole-animation files knows.
// (render: the mode-diff scale, which only shards that drew frames of the animation record).
constexpr const char* kShardOwnKeys[] = {"decode_check", "morph", "mode_diff_max_distance"};

const json* animation(const json& manifest, size_t input, size_t clip) {
  const json& inputs = manifest["inputs"];
  if (input >= inputs.size() || !inputs[input].contains("animations")) return nullptr;
  const json& clips = inputs[input]["animations"];
  return clips.is_array() && clip < clips.size() && clips[clip].is_object() ? &clips[clip] : nullptr;
}

json* animation(json& manifest, size_t input, size_t clip) {
  return const_cast<json*>(animation(std::as_const(manifest), input, clip));
}

// What every shard of one job must agree on: the manifest without its shard's share.
json shared_part(json manifest) {
  manifest.erase("shard");
  manifest.erase("outputs");
  for (json& in : manifest["inputs"])
    if (in.contains("animations") && in["animations"].is_array())
      for (json& clip : in["animations"])
        if (clip.is_object())
          for (const char* key : kShardOwnKeys) clip.erase(key);
  return manifest;
}

// Where `a` and `b` first differ, as "key.key[i]", with both values; empty when equal.
std::string first_difference(const json& a, const json& b, const std::string& at, std::string& a_value, std::string& b_value) {
  if (a.type() == b.type() && a.is_object()) {
    std::set<std::string> keys;
    for (const auto& [k, v] : a.items()) keys.insert(k);
    for (const auto& [k, v] : b.items()) keys.insert(k);
    for (const std::string& k : keys) {
      const std::string here = at.empty() ? k : at + "." + k;
      if (!a.contains(k) || !b.contains(k)) {
        a_value = a.contains(k) ? a[k].dump() : "absent";
        b_value = b.contains(k) ? b[k].dump() : "absent";
        return here;
      }
      if (std::string d = first_difference(a[k], b[k], here, a_value, b_value); !d.empty()) return d;
    }
    return {};
  }
  if (a.type() == b.type() && a.is_array() && a.size() == b.size()) {
    for (size_t i = 0; i < a.size(); ++i)
      if (std::string d = first_difference(a[i], b[i], at + "[" + std::to_string(i) + "]", a_value, b_value); !d.empty())
        return d;
    return {};
  }
  if (a == b) return {};
  a_value = a.dump(-1, ' ', false, json::error_handler_t::replace);
  b_value = b.dump(-1, ' ', false, json::error_handler_t::replace);
  return at.empty() ? "the whole manifest" : at;
}

std::string shortened(std::string s) {
  constexpr size_t kLongest = 80;
  return s.size() <= kLongest ? s : s.substr(0, kLongest - 3) + "...";
}

// The shards of one job (sorted by index, all N present) merged, or a refusal naming the shard that differs.
json merge_job(const std::string& folder, const std::vector<const JobManifest*>& shards, std::vector<std::string>& refusals) {
  const JobManifest& first = *shards.front();
  json merged = shared_part(first.json);
  for (size_t s = 1; s < shards.size(); ++s) {
    std::string first_value, this_value;
    const std::string at = first_difference(merged, shared_part(shards[s]->json), "", first_value, this_value);
    if (at.empty()) continue;
    const bool failed_input = at.size() > 6 && at.substr(at.size() - 6) == ".error";
    refusals.push_back(problem_location(folder, {shards[s]->name, {}, {}}) + ": " +
                       (failed_input ? "an input failed otherwise in this shard (run again the shard where it failed)"
                                     : "run with other flags, inputs or deformer") +
                       " than in " + first.name + " (" + at + ": " + shortened(this_value) + " here, " +
                       shortened(first_value) + " there)");
  }
  merged["shard"] = {{"index", 0}, {"count", 1}};

  std::map<std::string, json> outputs;  // by path: the bake's order
  for (const JobManifest* shard : shards)
    for (const json& out : shard->json["outputs"]) outputs.emplace(out["path"].get<std::string>(), out);
  json list = json::array();
  for (auto& [path, out] : outputs) list.push_back(std::move(out));
  merged["outputs"] = std::move(list);

  for (size_t i = 0; i < merged["inputs"].size(); ++i)
    for (size_t c = 0; json* clip = animation(merged, i, c); ++c)
      for (const char* key : kShardOwnKeys)
        for (const JobManifest* shard : shards)
          if (const json* own = animation(shard->json, i, c); own && own->contains(key)) {
            (*clip)[key] = (*own)[key];
            break;
          }
  return merged;
}

}  // namespace

MergeReport merge_shards(const std::string& given_folder, unsigned threads) {
  MergeReport report;
  const std::string folder = folder_name(given_folder);
  ManifestSet set = read_manifests(folder);
  std::map<std::string, std::vector<const JobManifest*>> jobs;  // base → its shard manifests, by index
  for (const JobManifest& m : set.manifests)
    if (m.sharded()) jobs[m.base].push_back(&m);
  if (jobs.empty()) {
    report.verify = verify_folder(folder, threads);
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
  report.verify = check_folder(folder, set, checked, threads);

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

  std::vector<std::pair<std::string, json>> written;
  for (const auto& [base, shards] : jobs)
    written.emplace_back(base + ".json", merge_job(folder, shards, report.refusals));
  if (!report.refusals.empty()) return report;

  for (const auto& [name, manifest] : written) {
    job_manifest::write(folder, name, manifest);
    for (const json& in : manifest["inputs"])
      if (in.contains("error") && in["path"].is_string() && in["error"].is_string())
        report.failed_inputs.emplace_back(in["path"].get<std::string>(), in["error"].get<std::string>());
  }
  for (const auto& [base, shards] : jobs) {
    for (const JobManifest* s : shards) {
      std::error_code ec;
      if (!fs::remove(fs::path(folder) / s->name, ec) && ec)
        throw OutputError(folder + "/" + s->name + ": cannot be deleted after the merge: " + ec.message());
    }
    report.merged.push_back({base + ".json", shards.size()});
  }
  return report;
}

}  // namespace dqskin
