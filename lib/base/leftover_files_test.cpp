// The names of what a killed writer leaves (".NAME.tmp-PID-N", ".NAME.old-PID-N"), and their removal when
// the job that owns NAME runs again.
#include "leftover_files.hpp"

#include "dqskin/atomic_file.hpp"
#include "../test_support/scratch_dir.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <vector>

namespace dqskin {
namespace {

namespace fs = std::filesystem;

TEST(LeftoverFiles, ParsesTheNamesWritersGive) {
  const auto tmp = leftover_files::parse(".frame_0001.glb.tmp-4242-7");
  ASSERT_TRUE(tmp);
  EXPECT_EQ(tmp->target, "frame_0001.glb");
  EXPECT_FALSE(tmp->old);
  const auto old = leftover_files::parse(".vat.json.old-1-0");
  ASSERT_TRUE(old);
  EXPECT_EQ(old->target, "vat.json");
  EXPECT_TRUE(old->old);
  for (const char* other : {"frame_0001.glb", ".tmp-1-2", "..tmp-1-2", ".a.tmp-x-1", ".a.tmp-1-", ".a.bak-1-2", ".a.tmp-1",
                            "a.tmp-1-2", ".hidden"})
    EXPECT_FALSE(leftover_files::parse(other)) << other;
}

// The temporary that AtomicFile makes is one parse() recognizes, for the output it writes.
TEST(LeftoverFiles, RecognizesAtomicFileTemporaries) {
  const testing_support::ScratchDir scratch("leftover");
  AtomicFile file((scratch.path() / "out.bin").string());
  file.write(std::string("x"));
  size_t seen = 0;
  for (const auto& e : fs::directory_iterator(scratch.path())) {
    const auto l = leftover_files::parse(e.path().filename().string());
    ASSERT_TRUE(l) << e.path();
    EXPECT_EQ(l->target, "out.bin");
    ++seen;
  }
  EXPECT_EQ(seen, 1u);
}

// Only the leftovers of the outputs named go, whichever process made them (a rerun in a container often
// has the killed run's process id).
TEST(LeftoverFiles, RemovesOnlyTheNamedOutputsLeftovers) {
  const testing_support::ScratchDir scratch("leftover");
  const fs::path clip = scratch.path() / "model" / "walk";
  fs::create_directories(clip);
  const std::string own = ".frame_0000.glb.tmp-" + std::to_string(::getpid()) + "-0";
  for (const std::string& name : std::vector<std::string>{".frame_0000.glb.tmp-1-0", ".frame_0000.glb.old-1-3", ".frame_0001.glb.tmp-1-0", own})
    std::ofstream(clip / name) << "partial";
  EXPECT_EQ(leftover_files::remove_for(scratch.path().string(), {"model/walk/frame_0000.glb"}), 3u);
  EXPECT_FALSE(fs::exists(clip / ".frame_0000.glb.tmp-1-0"));
  EXPECT_FALSE(fs::exists(clip / ".frame_0000.glb.old-1-3"));
  EXPECT_TRUE(fs::exists(clip / ".frame_0001.glb.tmp-1-0")) << "another output's";
  EXPECT_FALSE(fs::exists(clip / own)) << "one with this process's id";
  EXPECT_EQ(leftover_files::remove_for((scratch.path() / "absent").string(), {"x/y.glb"}), 0u) << "no folder: nothing";
}

}  // namespace
}  // namespace dqskin
