// The temporary and backup files this process has made and not yet renamed or deleted (internal to the
// output writers): a process that must end at once deletes them (remove_pending_files, atomic_file.hpp).
#pragma once

#include <string>

namespace dqskin::pending_files {

void add(const std::string& path);
void remove(const std::string& path);

}  // namespace dqskin::pending_files
