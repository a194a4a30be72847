#include "stderr_capture.hpp"

#include "stderr_lock.hpp"

#include <unistd.h>

#include <algorithm>
#include <iostream>

namespace dqskin {

std::mutex& stderr_mutex() {
  static std::mutex mutex;
  return mutex;
}

CapturedStderr::CapturedStderr() : lock_(stderr_mutex()) {
  std::fflush(stderr);
  std::cerr.flush();
  file_ = std::tmpfile();
  if (!file_) return;
  saved_ = ::dup(2);
  if (saved_ < 0 || ::dup2(::fileno(file_), 2) < 0) {
    if (saved_ >= 0) ::close(saved_);
    saved_ = -1;
    std::fclose(file_);
    file_ = nullptr;
  }
}

// Only restores stderr: nothing here allocates or throws.
CapturedStderr::~CapturedStderr() {
  if (!file_) return;
  std::fflush(stderr);
  ::dup2(saved_, 2);
  ::close(saved_);
  std::fclose(file_);
}

std::string CapturedStderr::finish() {
  if (!file_) return "";
  std::fflush(stderr);
  ::dup2(saved_, 2);
  ::close(saved_);
  std::string text;
  std::rewind(file_);
  char buffer[4096];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, file_)) > 0 && text.size() < (1u << 16);) text.append(buffer, n);
  std::fclose(file_);
  file_ = nullptr;
  if (lock_.owns_lock()) lock_.unlock();
  return text;
}

std::string with_library_text(std::string message, const std::string& captured) {
  for (size_t start = 0; start < captured.size();) {
    const size_t end = std::min(captured.find('\n', start), captured.size());
    std::string line = captured.substr(start, end - start);
    start = end + 1;
    while (!line.empty() && (line.back() == ' ' || line.back() == '\r')) line.pop_back();
    // "libpng error: IDAT: CRC error" says nothing new when OpenImageIO's message has "IDAT: CRC error".
    std::string said = line;
    for (const char* prefix : {"libpng error: ", "libpng warning: "})
      if (said.rfind(prefix, 0) == 0) said.erase(0, std::char_traits<char>::length(prefix));
    if (!said.empty() && message.find(said) == std::string::npos) message += "; " + line;
  }
  return message;
}

}  // namespace dqskin
