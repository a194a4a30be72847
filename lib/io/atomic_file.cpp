#include "dqskin/atomic_file.hpp"

#include "dqskin/error.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

namespace dqskin {
namespace {

[[noreturn]] void fail(const std::string& path, const char* what) {
  throw OutputError(path + ": " + what + ": " + std::strerror(errno));
}

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  // Unique per process and object, hidden, in the destination folder.
  static std::atomic<unsigned> counter{0};
  const size_t slash = path_.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "" : path_.substr(0, slash + 1);
  const std::string name = slash == std::string::npos ? path_ : path_.substr(slash + 1);
  temporary_ = folder + "." + name + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  file_ = std::fopen(temporary_.c_str(), "wb");
  if (!file_) fail(path_, "cannot create");
}

AtomicFile::~AtomicFile() {
  if (file_) {
    std::fclose(file_);
    std::remove(temporary_.c_str());
  }
}

void AtomicFile::write(std::span<const char> bytes) {
  if (!file_) throw OutputError(path_ + ": write after commit");
  if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) fail(path_, "cannot write");
}

void AtomicFile::commit() {
  if (!file_) throw OutputError(path_ + ": committed twice");
  const bool flushed = std::fflush(file_) == 0 && ::fsync(::fileno(file_)) == 0;
  const int error = errno;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed || !closed) {
    std::remove(temporary_.c_str());
    errno = flushed ? errno : error;
    fail(path_, "cannot write");
  }
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0) {
    const int rename_error = errno;
    std::remove(temporary_.c_str());
    errno = rename_error;
    fail(path_, "cannot rename into place");
  }
}

}  // namespace dqskin
