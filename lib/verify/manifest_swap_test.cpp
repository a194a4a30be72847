// The last step of dqskin merge: the merged manifests take the shard manifests' place all at once, and a
// cancel or a failure before the end leaves the folder as it was.
#include "manifest_swap.hpp"

#include "dqskin/error.hpp"
#include "dqskin/job.hpp"
#include "../test_support/read_file.hpp"
#include "../test_support/scratch_dir.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>

namespace dqskin::verify_detail {
namespace {

namespace fs = std::filesystem;

// Every entry of `dir` (not recursive), name → bytes ("folder" for a folder).
std::map<std::string, std::string> entries(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::directory_iterator(dir))
    out[e.path().filename().string()] = e.is_directory() ? "folder" : testing_support::read_file(e.path());
  return out;
}

class ManifestSwapTest : public testing::Test {
protected:
  void SetUp() override {
    for (const char* name : {"manifest.shard-0-of-2.json", "manifest.shard-1-of-2.json"}) std::ofstream(folder_ / name) << name;
    std::ofstream(folder_ / "manifest.json") << "an earlier merge's";
  }
  const testing_support::ScratchDir scratch_{"manifest_swap"};
  const fs::path folder_ = scratch_.path();
  const std::vector<std::string> shards_ = {"manifest.shard-0-of-2.json", "manifest.shard-1-of-2.json"};
};

TEST_F(ManifestSwapTest, TheMergedManifestReplacesTheShardsAndAnEarlierOne) {
  swap_in_manifests(folder_.string(), {{"manifest.json", "merged"}}, shards_, nullptr);
  const std::map<std::string, std::string> expected = {{"manifest.json", "merged"}};
  EXPECT_EQ(entries(folder_), expected) << "no shard manifest, temporary or file kept aside is left";
}

TEST_F(ManifestSwapTest, ACancelLeavesTheFolderAsItWas) {
  const auto before = entries(folder_);
  const std::atomic<bool> cancel{true};
  EXPECT_THROW(swap_in_manifests(folder_.string(), {{"manifest.json", "merged"}}, shards_, &cancel), JobCancelled);
  EXPECT_EQ(entries(folder_), before);
}

// The second manifest cannot take its name (a folder has it) after the first has taken its own and the
// shard manifests have moved aside: all of it is undone.
TEST_F(ManifestSwapTest, AFailureMidwayPutsEverythingBack) {
  fs::create_directory(folder_ / "render-manifest.json");
  std::ofstream(folder_ / "render-manifest.shard-0-of-2.json") << "render shard";
  const auto before = entries(folder_);
  EXPECT_THROW(swap_in_manifests(folder_.string(), {{"manifest.json", "merged"}, {"render-manifest.json", "merged render"}},
                                 {shards_[0], shards_[1], "render-manifest.shard-0-of-2.json"}, nullptr),
               OutputError);
  EXPECT_EQ(entries(folder_), before);
}

}  // namespace
}  // namespace dqskin::verify_detail
