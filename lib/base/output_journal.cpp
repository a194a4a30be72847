#include "output_journal.hpp"

#include "dqskin/error.hpp"
#include "file_kind.hpp"
#include "pending_files.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace dqskin {
namespace {

bool exists(const std::string& path) {
  struct stat st {};
  return ::lstat(path.c_str(), &st) == 0;
}

}  // namespace

OutputJournal::~OutputJournal() { roll_back(); }

void OutputJournal::make_folders(const std::string& folder) {
  // Another process may remove an empty ancestor between our look and our mkdir (it made the folder
  // and is rolling back, as two bakes into siblings of a new folder do); mkdir then says ENOENT, and we
  // look again. A few rounds settle it: each needs the other process to roll back again.
  for (int round = 0;; ++round) {
    // The missing ancestors, outermost first.
    std::vector<std::string> missing;
    for (std::filesystem::path p(folder); !p.empty() && !exists(p.string()); p = p.parent_path()) {
      missing.insert(missing.begin(), p.string());
      if (p == p.parent_path()) break;
    }
    bool vanished = false;
    for (const std::string& f : missing) {
      if (::mkdir(f.c_str(), 0777) == 0) {
        const std::lock_guard<std::mutex> lock(mutex_);
        folders_.push_back(f);
      } else if (errno == ENOENT && round < 16) {
        vanished = true;
        break;
      } else if (errno != EEXIST) {
        throw OutputError(f + ": cannot create folder: " + std::strerror(errno));
      }
    }
    if (!vanished) return;
  }
}

void OutputJournal::before_replacing(const std::string& path) {
  Entry entry{path, "", false, false};
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0) {
    if (!S_ISREG(st.st_mode)) throw OutputError(path + ": is " + file_kind(st.st_mode) + "; not replaced by a file");
    entry.backup = pending_files::hidden_name(path, "old");
    pending_files::add(entry.backup);  // a process that must end at once deletes it (the new file stays)
    if (::link(path.c_str(), entry.backup.c_str()) != 0) {
      // No hard links here (or links refused): the old file moves aside for a moment instead; a process
      // that must end at once puts it back unless its replacement has arrived.
      pending_files::add(entry.backup, path);
      if (std::rename(path.c_str(), entry.backup.c_str()) != 0) {
        const int error = errno;
        pending_files::remove(entry.backup);
        throw OutputError(path + ": cannot keep the old file aside: " + std::strerror(error));
      }
      entry.moved = true;
    }
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  files_.push_back(std::move(entry));
}

void OutputJournal::replaced(const std::string& path) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (auto it = files_.rbegin(); it != files_.rend(); ++it)
    if (it->path == path && !it->written) {
      it->written = true;
      return;
    }
}

void OutputJournal::keep() noexcept {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (const Entry& e : files_) {
    if (e.backup.empty()) continue;
    if (e.moved && !e.written) std::rename(e.backup.c_str(), e.path.c_str());  // the new one never came
    else ::unlink(e.backup.c_str());
    pending_files::remove(e.backup);
  }
  files_.clear();
  folders_.clear();
}

void OutputJournal::roll_back() noexcept {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (auto it = files_.rbegin(); it != files_.rend(); ++it) {
    if (it->backup.empty()) {
      if (it->written) ::unlink(it->path.c_str());
      continue;
    }
    // The old file takes its place again in one rename (atomic: there is no moment without either).
    if (it->written || it->moved) std::rename(it->backup.c_str(), it->path.c_str());
    else ::unlink(it->backup.c_str());  // linked, never replaced
    pending_files::remove(it->backup);
  }
  files_.clear();
  for (auto it = folders_.rbegin(); it != folders_.rend(); ++it) ::rmdir(it->c_str());  // only when empty
  folders_.clear();
}

}  // namespace dqskin
