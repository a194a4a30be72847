// One lock for everything written to stderr. While the library decodes or encodes an image it redirects
// file descriptor 2 for a moment, so that what libpng prints there ("libpng error: …") becomes part of
// dqskin's one-line message instead of a line of its own; an application thread that writes to stderr at
// the same time (a progress bar) holds this lock, so that its text is not swallowed.
#pragma once

#include <mutex>

namespace dqskin {

std::mutex& stderr_mutex();

}  // namespace dqskin
