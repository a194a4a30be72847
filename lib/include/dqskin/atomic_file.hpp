// Writing a file so that it appears complete or not at all (shared/DESIGN.md "Every output is written to
// a temporary name in the destination folder and renamed when complete").
#pragma once

#include <cstdio>
#include <span>
#include <string>

namespace dqskin {

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
  void commit();

  const std::string& path() const { return path_; }

private:
  std::string path_;
  std::string temporary_;
  std::FILE* file_ = nullptr;
};

}  // namespace dqskin
