// Checking and merging job folders (bake and render outputs) against their manifests: `dqskin verify` and
// `dqskin merge` as library calls. A folder is what its manifests say it is when every listed file is
// there with its size and SHA-256, no other file lies in the folders the manifests own (the inputs' output
// folders), no temporary file of an interrupted write is left, and every shard of a sharded job finished.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace dqskin {

// One way a folder differs from its manifests.
struct FolderProblem {
  std::string path;     // relative to the folder; empty for the folder itself
  std::string kind;     // missing, size, hash, unlisted, temporary, shard-missing, manifest, conflict
  std::string message;  // one line, for a person
};

struct VerifyReport {
  std::string folder;
  std::vector<std::string> manifests;  // the manifests read, by name
  size_t files = 0;                    // files listed by them
  uint64_t bytes = 0;                  // their sizes as listed
  std::vector<FolderProblem> problems;  // manifests' and shards' first, then by path and kind
  bool ok() const { return problems.empty(); }
};

// Checks `folder` against every manifest in it, hashing on `threads` threads (0: one per core). Throws
// InputError when `folder` is not a readable folder, or naming a manifest that takes more memory to read
// than --max-memory allows; JobCancelled once `cancel` (may be null; set from a signal handler) is set.
VerifyReport verify_folder(const std::string& folder, unsigned threads = 0, const std::atomic<bool>* cancel = nullptr);

// Where a problem is, for a person: FOLDER/PATH, or FOLDER for the folder itself.
std::string problem_location(const std::string& folder, const FolderProblem& problem);

// `dqskin verify --json`: {folder, ok, manifests, files, bytes, problems: [{path, kind, message}]}.
std::string verify_json(const VerifyReport& report);

// One job's shards merged into its whole manifest.
struct MergedJob {
  std::string manifest;                // the manifest written (manifest.json, render-manifest.json)
  size_t shards = 0;                   // how many shard manifests it replaced
};

struct MergeReport {
  VerifyReport verify;            // the shards' files, checked before anything is written
  std::vector<std::string> refusals;  // why nothing was merged (shards whose flags differ), each naming its file
  std::vector<MergedJob> merged;  // empty when there was nothing to merge or it was refused
  std::vector<std::pair<std::string, std::string>> failed_inputs;  // merged: inputs that failed in every shard, and why
  bool ok() const { return verify.ok() && refusals.empty(); }
};

// For every job in `folder` whose shards have run (bake: manifest.shard-I-of-N.json, render:
// render-manifest.shard-I-of-N.json): verifies their files, checks that all N shards finished with the
// same flags, inputs and deformer, and writes the manifest an unsharded run would have written (byte for
// byte), then deletes the shard manifests it replaces. Writes nothing when any check fails. The manifests
// change all at once: an error, or `cancel` (as verify_folder's) set before the end, leaves the folder as
// it was, and throws (OutputError, JobCancelled).
MergeReport merge_shards(const std::string& folder, unsigned threads = 0, const std::atomic<bool>* cancel = nullptr);

}  // namespace dqskin
