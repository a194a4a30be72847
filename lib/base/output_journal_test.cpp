#include "dqskin/atomic_file.hpp"
#include "output_journal.hpp"
#include "../test_support/scratch_dir.hpp"
#include "../test_support/read_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace dqskin {
namespace {

namespace fs = std::filesystem;

// Every entry under `dir` (hidden ones included) with its contents; folders as "(folder)".
std::map<std::string, std::string> tree(const fs::path& dir) {
  std::map<std::string, std::string> out;
  const std::string folder = "(folder)";
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = fs::relative(e.path(), dir).string();
    if (e.is_directory()) {
      out.emplace(name, folder);
      continue;
    }
    out[name] = testing_support::read_file(e.path());
  }
  return out;
}

void write(const fs::path& path, const std::string& text, OutputJournal& journal,
           Overwrite overwrite = Overwrite::kReplace) {
  AtomicFile file(path.string());
  file.write(text);
  file.commit({overwrite, &journal});
}

class OutputJournalTest : public testing::Test {
protected:
  void SetUp() override {
    fs::create_directories(dir_ / "Fox" / "Survey");
    std::ofstream(dir_ / "Fox" / "Survey" / "frame_0000.ply") << "old frame 0";
    std::ofstream(dir_ / "manifest.json") << "{}";
    before_ = tree(dir_);
  }

  const testing_support::ScratchDir scratch_{"journal"};
  const fs::path dir_ = scratch_.path();
  std::map<std::string, std::string> before_;
};

TEST_F(OutputJournalTest, RollBackRemovesNewFilesAndFoldersAndRestoresReplacedOnes) {
  {
    OutputJournal journal;
    journal.make_folders((dir_ / "Fox" / "Walk" / "deeper").string());
    write(dir_ / "Fox" / "Walk" / "deeper" / "frame_0000.ply", "new", journal);
    write(dir_ / "Fox" / "Survey" / "frame_0000.ply", "replaced frame 0", journal);  // --force
    write(dir_ / "Fox" / "Survey" / "frame_0001.ply", "new frame 1", journal);
    EXPECT_NE(tree(dir_), before_);
    journal.roll_back();
    EXPECT_EQ(tree(dir_), before_) << "the folder is as it was: no file, folder or backup left";
  }
  EXPECT_EQ(tree(dir_), before_) << "the destructor changes nothing more";
}

TEST_F(OutputJournalTest, DestroyedWithoutKeepRollsBack) {
  {
    OutputJournal journal;
    journal.make_folders((dir_ / "Fox" / "Run").string());
    write(dir_ / "Fox" / "Run" / "vat.json", "{}", journal);
  }
  EXPECT_EQ(tree(dir_), before_);
}

TEST_F(OutputJournalTest, KeepLeavesTheNewFilesAndDeletesTheOldOnes) {
  OutputJournal journal;
  write(dir_ / "Fox" / "Survey" / "frame_0000.ply", "replaced frame 0", journal);
  journal.keep();
  std::map<std::string, std::string> expected = before_;
  expected["Fox/Survey/frame_0000.ply"] = "replaced frame 0";
  EXPECT_EQ(tree(dir_), expected) << "no hidden backup stays";
  journal.roll_back();
  EXPECT_EQ(tree(dir_), expected) << "after keep() there is nothing to roll back";
}

TEST_F(OutputJournalTest, AnUnchangedFileThatWasThereStays) {
  {
    OutputJournal journal;
    write(dir_ / "Fox" / "Survey" / "frame_0000.ply", "old frame 0", journal, Overwrite::kRefuseDifferent);
  }
  EXPECT_EQ(tree(dir_), before_);
}

TEST_F(OutputJournalTest, PendingBackupsAreDeletedByAStopThatCannotWait) {
  OutputJournal journal;
  journal.before_replacing((dir_ / "manifest.json").string());
  EXPECT_EQ(tree(dir_).size(), before_.size() + 1) << "the old file is kept aside";
  remove_pending_files();
  EXPECT_EQ(tree(dir_), before_);
  journal.keep();
}

// Two bakes into siblings of a new folder, as two processes do: each makes the shared parent when it finds
// none and removes it again when it rolls back, so a parent one of them saw can vanish before its mkdir.
// Neither may fail for that.
TEST_F(OutputJournalTest, AParentRemovedByAnotherRollBackIsMadeAgain) {
  const fs::path parent = dir_ / "undeformable_out";
  std::vector<std::string> errors(2);
  auto bake = [&](std::size_t id) {
    for (int i = 0; i < 4000 && errors[id].empty(); ++i) {
      try {
        OutputJournal journal;
        journal.make_folders((parent / ("case_" + std::to_string(id))).string());
      } catch (const std::exception& e) {
        errors[id] = e.what();
      }
    }
  };
  std::thread other(bake, std::size_t{1});
  bake(std::size_t{0});
  other.join();
  EXPECT_EQ(errors[0], "");
  EXPECT_EQ(errors[1], "");
  // Each removes what it made; the parent stays (empty) when its maker's rmdir found the other's folder in it.
  EXPECT_FALSE(fs::exists(parent / "case_0"));
  EXPECT_FALSE(fs::exists(parent / "case_1"));
}

}  // namespace
}  // namespace dqskin
