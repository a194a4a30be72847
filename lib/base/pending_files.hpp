// The temporary and backup files this process has made and not yet renamed or deleted (internal to the
// output writers): a process that must end at once deletes them (remove_pending_files, atomic_file.hpp).
#pragma once

#include <string>

namespace dqskin::pending_files {

// ".NAME.KIND-PID-N" beside `path` ("tmp" for a temporary, "old" for a file kept aside): hidden, in the same
// folder (so a rename cannot cross file systems), unique per process and call.
std::string hidden_name(const std::string& path, const char* kind);

// `restore_to`: for an old file moved aside (renamed, not linked) while its replacement is written: a
// process that ends at once puts it back there if the replacement never arrived, and deletes it otherwise.
void add(const std::string& path, const std::string& restore_to = "");
void remove(const std::string& path);

}  // namespace dqskin::pending_files
