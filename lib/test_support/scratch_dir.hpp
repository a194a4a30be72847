// A folder of its own for one GoogleTest test (header-only, for the test executables): created empty when
// the test starts, removed with everything in it when it ends.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace dqskin::testing_support {

// TMPDIR/dqskin_<prefix>_<pid>_<test name>: the process id keeps parallel test processes apart, the test
// name the tests of one process. Construct it while a test runs (a fixture member is).
class ScratchDir {
public:
  explicit ScratchDir(const std::string& prefix)
      : path_(std::filesystem::temp_directory_path() /
              ("dqskin_" + prefix + "_" + std::to_string(::getpid()) + "_" + test_name())) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;  // a destructor must not throw; a leftover folder is only untidy
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

private:
  // A parameterized test is named "Name/3": the slash would make a subfolder, and removing it would leave
  // the parent behind.
  static std::string test_name() {
    std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    for (char& c : name)
      if (c == '/') c = '_';
    return name;
  }

  std::filesystem::path path_;
};

}  // namespace dqskin::testing_support
