// What a path names, in words, and where the file system begins below a path that does not exist yet
// (internal to the readers and the output planning).
#pragma once

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace dqskin {

// "a folder", "a device", "a FIFO", "a socket", or "not a regular file", for a mode that is not a regular
// file's.
inline const char* file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// `path` itself, or its nearest ancestor that exists (an output folder before it is created), for
// questions about its file system (free space, longest name).
inline std::string nearest_existing(const std::string& path) {
  std::filesystem::path p = path.empty() ? "." : path;
  while (!p.empty() && ::access(p.c_str(), F_OK) != 0 && p != p.parent_path()) p = p.parent_path();
  return p.empty() ? "." : p.string();
}

}  // namespace dqskin
