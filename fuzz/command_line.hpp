// What the command-line fuzz targets share: a scratch folder per process, run_cli with an argument list,
// and the exit statuses a user may see. A status other than 0, 1 (some inputs failed) and 2 (input error)
// aborts, as does anything escaping run_cli; sanitizer reports, hangs and leaks are libFuzzer's findings.
#pragma once

#include "commands.hpp"

#include <fcntl.h>
#include <stdlib.h>  // mkdtemp
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace dqskin::fuzz {

namespace fs = std::filesystem;

// One scratch folder per process, removed when the process exits.
inline const fs::path& scratch() {
  // Never destroyed: the exit handler registered while it is made runs after static destructors would.
  static const fs::path* const folder = [] {
    std::string name = (fs::temp_directory_path() / "dqskin-fuzz-XXXXXX").string();
    if (!::mkdtemp(name.data())) std::abort();
    const fs::path* path = new fs::path(name);
    std::atexit([] {
      std::error_code ignored;
      fs::remove_all(scratch(), ignored);
    });
    return path;
  }();
  return *folder;
}

inline int run(std::vector<std::string> args) {
  args.insert(args.begin(), "dqskin");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  argv.push_back(nullptr);
  return cli::run_cli(int(args.size()), argv.data());
}

// A copy of stderr made before libFuzzer's -close_fd_mask=3 closes it, for the targets' own diagnosis.
inline int& saved_stderr() {
  static int fd = 2;
  return fd;
}

inline void keep_stderr() {
  if (const int fd = ::fcntl(2, F_DUPFD_CLOEXEC, 3); fd >= 0) saved_stderr() = fd;
}

inline void expect_status(const char* target, int status) {
  if (status < 0 || status > 2) {
    dprintf(saved_stderr(), "%s: exit status %d\n", target, status);
    std::abort();
  }
}

inline void write_file(const fs::path& path, const uint8_t* data, size_t size) {
  std::ofstream file(path, std::ios::binary);
  file.write(reinterpret_cast<const char*>(data), std::streamsize(size));
}

}  // namespace dqskin::fuzz
