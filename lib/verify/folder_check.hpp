// The checks of `dqskin verify` on a chosen set of manifests (internal): merge checks a folder against the
// shards it merges, leaving out the whole manifest it is about to replace.
#pragma once

#include "manifest_set.hpp"

#include <atomic>

namespace dqskin::verify_detail {

// Checks `folder` against `manifests`: their listed files (size, then SHA-256, on `threads` threads),
// unlisted files and leftovers in the folders their inputs own, and shards that did not finish. The
// report's problems include `set.problems` and `set.root_leftovers`. Throws JobCancelled once `cancel`
// (may be null) is set.
VerifyReport check_folder(const std::filesystem::path& folder, const ManifestSet& set,
                          const std::vector<const JobManifest*>& manifests, unsigned threads,
                          const std::atomic<bool>* cancel = nullptr);

}  // namespace dqskin::verify_detail
