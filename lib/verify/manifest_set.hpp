// The manifests of a job folder (internal to verify and merge): bake's manifest.json and render's
// render-manifest.json, whole or per shard (BASE.shard-I-of-N.json), read and checked for the shape the
// checks rely on, so that a hostile or damaged manifest yields a problem line, not a crash or a read
// outside the folder.
#pragma once

#include "dqskin/job.hpp"
#include "dqskin/verify.hpp"

#include <nlohmann/json.hpp>

#include <atomic>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dqskin::verify_detail {

// The jobs that write manifests, by the base of their manifest's name.
inline constexpr std::string_view kJobBases[] = {"manifest", "render-manifest"};

struct JobManifest {
  std::string name;  // file name in the folder
  std::string base;  // one of kJobBases
  Shard shard;       // {0, 1} for a whole job's manifest
  nlohmann::json json;
  bool sharded() const { return !shard.whole(); }
};

// What a manifest's name says: its job and shard; nullopt for any other name.
std::optional<JobManifest> parse_manifest_name(std::string_view name);

struct ManifestSet {
  std::vector<JobManifest> manifests;  // well-formed ones, sorted by name
  std::vector<FolderProblem> problems;  // manifests that cannot be read or do not have a manifest's shape
  std::vector<std::string> root_leftovers;  // temporaries left in the folder itself

  ManifestSet() = default;
  ManifestSet(ManifestSet&&) = default;
  ManifestSet& operator=(ManifestSet&&) = default;
  ~ManifestSet();  // frees the documents whatever --max-memory says (free_unbounded.hpp)
};

// Reads every manifest in `folder`. Throws InputError when the folder cannot be listed, and naming the
// manifest when reading it takes more memory than --max-memory allows; JobCancelled once `cancel` (may be
// null) is set.
ManifestSet read_manifests(const std::filesystem::path& folder, const std::atomic<bool>* cancel = nullptr);

// `folder` as messages name it: without trailing slashes ("out/" is "out"; "/" stays).
std::string folder_name(std::string folder);

// A path a manifest may name: relative, '/'-separated, no empty, "." or ".." part.
bool is_contained_path(std::string_view path);

}  // namespace dqskin::verify_detail
