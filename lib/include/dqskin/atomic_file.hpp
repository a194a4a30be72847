// Writing a file so that it appears complete or not at all (docs/DESIGN.md §6.1: every output
// is written to a temporary name in the destination folder and renamed when complete).
#pragma once

#include <cstdio>
#include <span>
#include <string>

namespace dqskin {

// What commit() does when a file already exists under the final name.
enum class Overwrite {
  kReplace,          // replace it
  kRefuseDifferent,  // keep it when its bytes equal ours (nothing is written, its time stamp stays, so
                     // reruns and make-style rules see no change); throw OutputError when they differ
};

// What commit() did.
enum class Committed { kWritten, kUnchanged };

class OutputJournal;

// How commit() treats an existing file, and the journal (output_journal.hpp) that records what it changed
// so that a failed input can take it back; none when null. Converts from an Overwrite.
struct CommitOptions {
  CommitOptions(Overwrite overwrite_ = Overwrite::kReplace, OutputJournal* journal_ = nullptr)  // NOLINT: implicit
      : overwrite(overwrite_), journal(journal_) {}
  Overwrite overwrite;
  OutputJournal* journal;
};

// Opens a temporary file beside `path` (same folder, so the rename cannot cross file systems). commit()
// flushes it to disk and renames it to `path`; destroying an uncommitted AtomicFile removes the temporary,
// so a failed or interrupted write leaves nothing under the final name. Throws OutputError naming `path`.
class AtomicFile {
public:
  // `sync`: commit() fsyncs the data before the rename, so that after a power loss the file is whole or
  // absent. A caller writing many files may pass false and sync the file system once (sync_folder)
  // before writing the record that claims them; the rename alone is already atomic for other processes.
  explicit AtomicFile(std::string path, bool sync = true);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void write(std::span<const char> bytes);
  void write(const std::string& text) { write(std::span<const char>(text.data(), text.size())); }
  Committed commit(const CommitOptions& options = {});

  // For writers that open files themselves (OpenImageIO): closes our stream so that they can write the
  // temporary by name; commit() then flushes it to disk and renames it as usual.
  const std::string& hand_over();

  // True when a file exists under the final name with bytes other than the temporary's (after writing):
  // what commit(kRefuseDifferent) refuses. Lets a writer of several files check them all first.
  bool conflicts() const;

  const std::string& path() const { return path_; }
  // Where the bytes are until commit(): for a writer that reads back what it wrote (a page embedding an
  // image) before committing them together.
  const std::string& temporary() const { return temporary_; }

private:
  std::string path_;
  std::string temporary_;
  std::FILE* file_ = nullptr;
  bool open_ = false;  // the temporary exists and is not committed
  bool sync_ = true;
};

// Flushes every file of the file system holding `folder` to disk (syncfs). Throws OutputError.
void sync_folder(const std::string& folder);

// Deletes every temporary this process has open, and every old file an OutputJournal keeps aside (one
// moved aside whose replacement never came is put back), for a process that must end at once (a stop that
// cannot wait for the work to unwind). Files under final names are left as they are. With `hold`, no
// temporary can be made afterwards: a thread that tries waits for the process to end. Thread-safe; never
// throws.
void remove_pending_files(bool hold = false) noexcept;

}  // namespace dqskin
