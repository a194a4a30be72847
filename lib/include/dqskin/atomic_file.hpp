// Writing a file so that it appears complete or not at all (shared/DESIGN.md "Every output is written to
// a temporary name in the destination folder and renamed when complete").
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

// Opens a temporary file beside `path` (same folder, so the rename cannot cross file systems). commit()
// flushes it to disk and renames it to `path`; destroying an uncommitted AtomicFile removes the temporary,
// so a failed or interrupted write leaves nothing under the final name. Throws OutputError naming `path`.
class AtomicFile {
public:
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void write(std::span<const char> bytes);
  void write(const std::string& text) { write(std::span<const char>(text.data(), text.size())); }
  Committed commit(Overwrite overwrite = Overwrite::kReplace);

  // For writers that open files themselves (OpenImageIO): closes our stream so that they can write the
  // temporary by name; commit() then flushes it to disk and renames it as usual.
  const std::string& hand_over();

  const std::string& path() const { return path_; }

private:
  std::string path_;
  std::string temporary_;
  std::FILE* file_ = nullptr;
  bool open_ = false;  // the temporary exists and is not committed
};

}  // namespace dqskin
