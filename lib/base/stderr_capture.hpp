// Library messages captured from stderr (internal to the image readers and writers): libpng, through
// OpenImageIO, prints "libpng error: …" itself before OpenImageIO reports the failure.
#pragma once

#include <cstdio>
#include <mutex>
#include <string>

namespace dqskin {

// Redirects file descriptor 2 into a temporary file, holding stderr_mutex(), from construction until
// finish() or destruction. When the redirection cannot be made, nothing is captured and stderr is left
// alone.
class CapturedStderr {
public:
  CapturedStderr();
  ~CapturedStderr();
  CapturedStderr(const CapturedStderr&) = delete;
  CapturedStderr& operator=(const CapturedStderr&) = delete;

  // Restores stderr and returns what was written meanwhile.
  std::string finish();

private:
  std::unique_lock<std::mutex> lock_;
  std::FILE* file_ = nullptr;
  int saved_ = -1;
};

// `message` with each line of the captured library text added ("…; libpng error: IDAT: CRC error"),
// unless the message already says it: one line in all.
std::string with_library_text(std::string message, const std::string& captured);

}  // namespace dqskin
