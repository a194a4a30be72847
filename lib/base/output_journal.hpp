// What one input's outputs changed in the output folder, so that a failure can take it back
// (docs/DESIGN.md §6.2: a failed input leaves no file behind; docs/SECURITY.md, "Outputs"): the folders it
// created, the files it wrote, and, for files it replaced (--force), the old ones, kept aside under hidden
// names until the input has succeeded.
#pragma once

#include <mutex>
#include <string>
#include <vector>

namespace dqskin {

class OutputJournal {
public:
  OutputJournal() = default;
  // Rolls back, unless keep() was called.
  ~OutputJournal();
  OutputJournal(const OutputJournal&) = delete;
  OutputJournal& operator=(const OutputJournal&) = delete;

  // Creates `folder` and whichever of its parents are missing, remembering the ones it made. Throws
  // OutputError naming the folder.
  void make_folders(const std::string& folder);

  // For AtomicFile::commit, just before it renames a temporary to `path`: when `path` exists, it is kept
  // aside (a hard link under a hidden name beside it). Throws OutputError.
  void before_replacing(const std::string& path);
  // After the rename: `path` now holds the new file.
  void replaced(const std::string& path);

  // The input succeeded: deletes the old files kept aside, forgets everything.
  void keep() noexcept;
  // The input failed: removes the files written and the folders made, puts the old files back. Never
  // throws; what cannot be undone stays (a folder someone else wrote into meanwhile).
  void roll_back() noexcept;

private:
  struct Entry {
    std::string path;
    std::string backup;  // the old file, or empty when `path` is new
    bool moved = false;  // the old file was renamed aside (no hard links here), not linked
    bool written = false;
  };
  std::mutex mutex_;  // commits come from several encoding threads
  std::vector<Entry> files_;
  std::vector<std::string> folders_;  // outermost first
};

}  // namespace dqskin
