#include "dqskin/atomic_file.hpp"

#include "dqskin/error.hpp"
#include "output_journal.hpp"
#include "pending_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <mutex>
#include <map>
#include <vector>

namespace dqskin {
namespace {

[[noreturn]] void fail(const std::string& path, const char* what, int error) {
  throw OutputError(path + ": " + what + ": " + std::strerror(error));
}

// Byte-for-byte comparison of two files, in chunks.
bool same_contents(const std::string& a, const std::string& b) {
  std::ifstream fa(a, std::ios::binary), fb(b, std::ios::binary);
  if (!fa || !fb) return false;
  std::vector<char> ba(1 << 16), bb(1 << 16);
  while (true) {
    fa.read(ba.data(), std::streamsize(ba.size()));
    fb.read(bb.data(), std::streamsize(bb.size()));
    if (fa.gcount() != fb.gcount()) return false;
    if (std::memcmp(ba.data(), bb.data(), size_t(fa.gcount())) != 0) return false;
    if (!fa || !fb) return !fa && !fb;
  }
}

struct Pending {
  std::mutex mutex;
  std::map<std::string, std::string> paths;  // path → where to restore it ("" to delete it)
};
Pending& pending() {
  static Pending* p = new Pending;  // never destroyed: a stopping thread may use it during exit
  return *p;
}

}  // namespace

namespace pending_files {

std::string hidden_name(const std::string& path, const char* kind) {
  static std::atomic<unsigned> counter{0};
  const size_t slash = path.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "" : path.substr(0, slash + 1);
  const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  return folder + "." + name + "." + kind + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

void add(const std::string& path, const std::string& restore_to) {
  const std::lock_guard<std::mutex> lock(pending().mutex);
  pending().paths[path] = restore_to;
}

void remove(const std::string& path) {
  const std::lock_guard<std::mutex> lock(pending().mutex);
  pending().paths.erase(path);
}

}  // namespace pending_files

void remove_pending_files(bool hold) noexcept {
  pending().mutex.lock();
  for (const auto& [path, restore_to] : pending().paths) {
    if (!restore_to.empty() && ::access(restore_to.c_str(), F_OK) != 0) std::rename(path.c_str(), restore_to.c_str());
    else ::unlink(path.c_str());
  }
  pending().paths.clear();
  if (!hold) pending().mutex.unlock();  // held: any thread that tries to make another temporary waits for the end
}

AtomicFile::AtomicFile(std::string path, bool sync) : path_(std::move(path)), sync_(sync) {
  temporary_ = pending_files::hidden_name(path_, "tmp");
  pending_files::add(temporary_);
  file_ = std::fopen(temporary_.c_str(), "wb");
  if (!file_) {
    const int error = errno;
    pending_files::remove(temporary_);
    fail(path_, "cannot create", error);
  }
  open_ = true;
}

AtomicFile::~AtomicFile() {
  if (file_) std::fclose(file_);
  if (open_) std::remove(temporary_.c_str());
  pending_files::remove(temporary_);
}

void AtomicFile::write(std::span<const char> bytes) {
  if (!file_) throw OutputError(path_ + ": write after commit or hand-over");
  if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size())
    fail(path_, "cannot write", errno);
}

bool AtomicFile::conflicts() const {
  if (file_) std::fflush(file_);  // what write() buffered must be in the temporary to be compared
  return ::access(path_.c_str(), F_OK) == 0 && !same_contents(temporary_, path_);
}

const std::string& AtomicFile::hand_over() {
  if (!file_) throw OutputError(path_ + ": handed over after commit");
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!closed) fail(path_, "cannot write", errno);
  return temporary_;
}

Committed AtomicFile::commit(const CommitOptions& options) {
  if (!open_) throw OutputError(path_ + ": committed twice");
  // Flush our stream, or the hand-over writer's file, to disk before it gets its final name.
  if (file_) {
    const bool flushed = std::fflush(file_) == 0 && (!sync_ || ::fsync(::fileno(file_)) == 0);
    const int error = errno;
    const bool closed = std::fclose(file_) == 0;
    file_ = nullptr;
    if (!flushed || !closed) fail(path_, "cannot write", flushed ? errno : error);
  } else if (sync_) {
    const int fd = ::open(temporary_.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) fail(path_, "cannot write", errno);
    const bool synced = ::fsync(fd) == 0;
    const int error = errno;
    ::close(fd);
    if (!synced) fail(path_, "cannot write", error);
  }
  if (options.overwrite == Overwrite::kRefuseDifferent && ::access(path_.c_str(), F_OK) == 0) {
    if (conflicts()) throw OutputError(path_ + ": exists with different contents; not overwritten");
    return Committed::kUnchanged;  // the destructor removes the temporary
  }
  if (options.journal) options.journal->before_replacing(path_);
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0) fail(path_, "cannot rename into place", errno);
  open_ = false;
  pending_files::remove(temporary_);
  if (options.journal) options.journal->replaced(path_);
  return Committed::kWritten;
}

void sync_folder(const std::string& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) fail(folder, "cannot open", errno);
  const bool synced = ::syncfs(fd) == 0;
  const int error = errno;
  ::close(fd);
  if (!synced) fail(folder, "cannot sync", error);
}

}  // namespace dqskin
