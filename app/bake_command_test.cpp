// `dqskin bake` as a process: what a killed or interrupted bake leaves behind, and that a rerun
// completes it. Runs the real binary (DQSKIN_CLI) on the twisted cylinder at a high frame rate, so that
// the bake is still writing when the signal arrives.
#include "../lib/test_support/read_file.hpp"
#include "../lib/test_support/scratch_dir.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>
#include <vector>

extern char** environ;

namespace {

namespace fs = std::filesystem;

const std::string kInput = std::string(DQSKIN_TESTDATA_DIR) + "/twisted_cylinder.gltf";

pid_t start_bake(const fs::path& out) {
  const std::string out_arg = out.string();
  // Thousands of frames of three per-frame formats: several seconds of writing.
  const char* argv[] = {DQSKIN_CLI, "bake",   kInput.c_str(), "-o", out_arg.c_str(), "--fps", "3000",
                        "--format", "glb,ply,obj", "--quiet", nullptr};
  pid_t pid = 0;
  EXPECT_EQ(posix_spawn(&pid, DQSKIN_CLI, nullptr, nullptr, const_cast<char**>(argv), environ), 0);
  return pid;
}

int run_bake(const fs::path& out) {
  const pid_t pid = start_bake(out);
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

size_t count_frames(const fs::path& dir) {
  if (!fs::exists(dir)) return 0;
  size_t n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir)) n += e.path().extension() == ".ply";
  return n;
}

// Waits until the bake has written some frames (and is surely mid-way).
void wait_for_frames(const fs::path& out, size_t frames) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (count_frames(out) < frames && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_GE(count_frames(out), frames) << "the bake wrote nothing in two minutes";
}

// A temporary (".NAME.tmp-PID-N") or an old file kept aside while --force replaces it (".NAME.old-PID-N").
bool is_temporary(const fs::path& p) {
  const std::string name = p.filename().string();
  return name[0] == '.' && (name.find(".tmp-") != std::string::npos || name.find(".old-") != std::string::npos);
}

std::map<std::string, std::string> final_files(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file() || is_temporary(e.path()) || e.path().filename() == "manifest.json") continue;
    out[fs::relative(e.path(), dir).string()] = dqskin::testing_support::read_file(e.path());
  }
  return out;
}

// Keeps every core busy while it lives: a machine running other work, on which the last thread of a dying
// process may wait to be scheduled (Mesa's shader-cache thread, at nice 19, freeing a gigabyte took seconds).
class BusyCores {
public:
  BusyCores() {
    for (unsigned i = 0; i < std::max(1u, std::thread::hardware_concurrency()); ++i)
      threads_.emplace_back([this] {
        while (!stop_.load(std::memory_order_relaxed)) {
        }
      });
  }
  ~BusyCores() {
    stop_ = true;
    for (std::thread& t : threads_) t.join();
  }
  BusyCores(const BusyCores&) = delete;
  BusyCores& operator=(const BusyCores&) = delete;

private:
  std::atomic<bool> stop_{false};
  std::vector<std::thread> threads_;
};

// Starts a bake into `out`, waits until it is mid-way and sends it `signal`; returns its wait status.
int bake_and_signal(const fs::path& out, int signal) {
  const pid_t pid = start_bake(out);
  wait_for_frames(out, 50);
  EXPECT_EQ(kill(pid, signal), 0);
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

class BakeProcessTest : public testing::Test {
protected:
  const dqskin::testing_support::ScratchDir scratch_{"bake_process"};
  const fs::path root_ = scratch_.path();
};

TEST_F(BakeProcessTest, KilledBakeLeavesOnlyCompleteFilesAndARerunCompletesIt) {
  const fs::path out = root_ / "killed";
  const int status = bake_and_signal(out, SIGKILL);
  ASSERT_TRUE(WIFSIGNALED(status));
  const size_t frames_before = count_frames(out);

  // Every file under its final name is complete: a rerun without --force would refuse any file whose
  // bytes differ from the bake's, and it succeeds.
  ASSERT_EQ(run_bake(out), 0);
  EXPECT_GT(count_frames(out), frames_before) << "the rerun finished the job";
  ASSERT_EQ(run_bake(root_ / "reference"), 0);
  EXPECT_TRUE(final_files(out) == final_files(root_ / "reference"));
  EXPECT_TRUE(fs::exists(out / "manifest.json"));
}

// The case: SIGTERM during a bake of BrainStem into VAT and glb took up to 12.6 s to end the
// process (a batch on the GPU, a texture being compressed). Whatever the stage, it now ends within a second,
// by the signal, with no temporary left.
TEST_F(BakeProcessTest, StopsWithinASecondOfTheSignalWhateverTheStage) {
  const fs::path input = fs::path(DQSKIN_SHARED_TESTDATA_DIR) / "BrainStem" / "BrainStem.glb";
  if (!fs::exists(input)) GTEST_SKIP() << "shared test data not found: " << input;
  const std::string input_arg = input.string();
  for (const auto& [delay_ms, signal] : {std::pair{300, SIGTERM}, {1000, SIGTERM}, {2000, SIGINT}, {3000, SIGTERM}}) {
    const std::string out = (root_ / ("stop_" + std::to_string(delay_ms))).string();
    const char* argv[] = {DQSKIN_CLI, "bake", input_arg.c_str(), "-o", out.c_str(), "--format", "vat,glb", "--quiet", nullptr};
    pid_t pid = 0;
    ASSERT_EQ(posix_spawn(&pid, DQSKIN_CLI, nullptr, nullptr, const_cast<char**>(argv), environ), 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    const auto sent = std::chrono::steady_clock::now();
    ASSERT_EQ(kill(pid, signal), 0);
    int status = 0;
    {
      const BusyCores busy;  // as in CI, where other tests run beside this one
      waitpid(pid, &status, 0);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) continue;  // finished before the signal: nothing to time
    EXPECT_LT(seconds, 1.0) << "signal " << signal << " after " << delay_ms << " ms";
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal) << "after " << delay_ms << " ms: status " << status;
    if (!fs::exists(out)) continue;
    for (const auto& e : fs::recursive_directory_iterator(out)) EXPECT_FALSE(is_temporary(e.path())) << e.path();
  }
}

TEST_F(BakeProcessTest, InterruptedBakeRemovesItsTemporariesAndDiesOfTheSignal) {
  const fs::path out = root_ / "interrupted";
  const int status = bake_and_signal(out, SIGTERM);
  ASSERT_TRUE(WIFSIGNALED(status)) << "exit status " << WEXITSTATUS(status);
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  for (const auto& e : fs::recursive_directory_iterator(out)) EXPECT_FALSE(is_temporary(e.path())) << e.path();
  EXPECT_FALSE(fs::exists(out / "manifest.json")) << "an interrupted bake claims nothing";
  ASSERT_EQ(run_bake(out), 0);
}

}  // namespace
