// dqskin verify and merge under --max-memory's ceiling (the test binary links the counting allocator):
// whatever the ceiling, a run either succeeds or is refused by an exception the command turns into one
// line (a manifest too large to read is named), never ends the process, and a refused merge leaves the
// folder as it was.
#include "dqskin/verify.hpp"

#include "dqskin/error.hpp"
#include "dqskin/memory_ceiling.hpp"
#include "../test_support/read_file.hpp"
#include "../test_support/scratch_dir.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <new>

namespace dqskin {
namespace {

namespace fs = std::filesystem;

constexpr const char* kEmptySha256 = "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855";

// Every entry under `dir`, relative path → bytes ("folder" for a folder).
std::map<std::string, std::string> tree(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    out[fs::relative(e.path(), dir).generic_string()] = e.is_directory() ? "folder" : testing_support::read_file(e.path());
  return out;
}

class VerifyMemoryTest : public testing::Test {
protected:
  // `files` empty files under o/, listed by the two shard manifests of a bake, every other one each; the
  // input's record, which every shard has and the merged manifest copies, holds `numbers` frame numbers.
  void make_shards(size_t files, size_t numbers = 0) {
    fs::create_directories(root_ / "o");
    nlohmann::json input = {{"animations", nlohmann::json::array()}, {"output_folder", "o"}, {"path", "in.glb"}};
    for (size_t i = 0; i < numbers; ++i) input["frame_numbers"].push_back(i);
    for (size_t s = 0; s < 2; ++s) {
      nlohmann::json outputs = nlohmann::json::array();
      for (size_t i = s; i < files; i += 2) {
        const std::string path = "o/" + std::to_string(i);
        std::ofstream(root_ / path);
        outputs.push_back({{"path", path}, {"size", 0}, {"sha256", kEmptySha256}});
      }
      const nlohmann::json manifest = {{"inputs", {input}}, {"outputs", outputs}, {"shard", {{"index", s}, {"count", 2}}}};
      std::ofstream(root_ / ("manifest.shard-" + std::to_string(s) + "-of-2.json")) << manifest.dump();
    }
  }

  const testing_support::ScratchDir scratch_{"verify_memory"};
  const fs::path root_ = scratch_.path();
};

TEST_F(VerifyMemoryTest, AManifestTooLargeToReadIsNamed) {
  make_shards(20000);
  try {
    const MemoryCeiling ceiling(1 << 20);
    verify_folder(root_.string(), 1);
    FAIL() << "20,000 entries read within 1 MiB";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/manifest.shard-0-of-2.json: needs more memory than --max-memory 1.00 MiB allows"),
              std::string::npos)
        << e.what();
  }
}

// Each ceiling stops the work at another allocation: reading a manifest, listing and hashing the files,
// merging, writing the merged manifest, freeing the documents (nlohmann allocates to free one). The shared
// record is large, so that merging and writing take more than hashing does (its buffer is 1 MiB).
TEST_F(VerifyMemoryTest, EveryCeilingEndsInASuccessOrARefusalAndARefusedMergeChangesNothing) {
  make_shards(200, 100000);
  const auto before = tree(root_);
  size_t refused = 0;
  for (uint64_t ceiling = 64 << 10; ceiling < (16 << 20); ceiling += ceiling / 10) {
    bool merged = false;
    try {
      const MemoryCeiling limit(ceiling);
      merged = merge_shards(root_.string(), 1).ok();
    } catch (const InputError&) {
    } catch (const std::bad_alloc&) {
    }
    const MemoryCeilingLifted lifted;
    (void)out_of_memory_message();  // forgets the refusal, as the command does
    if (merged) {
      EXPECT_TRUE(fs::exists(root_ / "manifest.json")) << ceiling;
      break;
    }
    ++refused;
    ASSERT_EQ(tree(root_), before) << "refused at a ceiling of " << ceiling << " bytes";
  }
  EXPECT_GT(refused, 10u) << "the ceilings tried refused the merge at many points";
  EXPECT_TRUE(fs::exists(root_ / "manifest.json")) << "the largest ceiling merged";
}

}  // namespace
}  // namespace dqskin
