// The last step of dqskin merge (internal): the merged manifests take the place of the shard manifests
// they replace, all at once or not at all, whatever stops the process meanwhile.
#pragma once

#include <atomic>
#include <string>
#include <vector>

namespace dqskin::verify_detail {

struct ManifestText {
  std::string name;  // in the folder: manifest.json, render-manifest.json
  std::string text;  // job_manifest::text
};

// Writes each of `written` as `folder`/NAME and deletes each of `replaced` (names in `folder`), all or
// nothing. The texts are written to temporaries and flushed to disk first; then, in a step of a few
// renames, the replaced manifests move aside under hidden names and the new ones take their names. A
// failure in that step, or `cancel` (may be null) set before it ends, puts the folder back as it was and
// throws (OutputError, JobCancelled, std::bad_alloc); a process that must end at once meanwhile
// (remove_pending_files) removes the temporaries and moves the replaced manifests back. Then the files
// moved aside are deleted.
void swap_in_manifests(const std::string& folder, const std::vector<ManifestText>& written,
                       const std::vector<std::string>& replaced, const std::atomic<bool>* cancel);

}  // namespace dqskin::verify_detail
