// Files that a writer killed mid-write leaves beside its outputs: temporaries ".NAME.tmp-PID-N" and, under
// --force, old files kept aside ".NAME.old-PID-N" (pending_files.hpp names them). A process that ends
// normally, or on a signal, removes its own; only SIGKILL, a crash or a power loss leaves them.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dqskin::leftover_files {

struct Leftover {
  std::string target;  // NAME, the output it was written for
  bool old = false;    // an old file kept aside, not a temporary
};

// The leftover that `file_name` (no folder) names, if it is one.
std::optional<Leftover> parse(std::string_view file_name);

// Deletes the leftovers of `outputs` (paths relative to `root`): called once the outputs are committed,
// when this process has none of their temporaries open, so that rerunning a killed job leaves its folder
// clean. Only this job writes these outputs (a shard owns its files), so the leftovers can only be from an
// earlier run of it that was killed, whatever its process id was (in a container, often the same as
// ours). Returns how many were deleted; never throws.
size_t remove_for(const std::string& root, const std::vector<std::string>& outputs) noexcept;

}  // namespace dqskin::leftover_files
