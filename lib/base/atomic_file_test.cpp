#include "dqskin/atomic_file.hpp"
#include "dqskin/error.hpp"
#include "../test_support/scratch_dir.hpp"
#include "../test_support/read_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace dqskin {
namespace {

namespace fs = std::filesystem;

class AtomicFileTest : public testing::Test {
protected:

  std::string read(const fs::path& p) { return testing_support::read_file(p); }
  size_t entries() { return size_t(std::distance(fs::directory_iterator(dir_), fs::directory_iterator())); }

  const testing_support::ScratchDir scratch_{"atomic"};
  const fs::path dir_ = scratch_.path();
};

TEST_F(AtomicFileTest, CommittedFileAppearsWhole) {
  const fs::path out = dir_ / "frame_0001.ply";
  {
    AtomicFile file(out.string());
    file.write(std::string("hello "));
    EXPECT_FALSE(fs::exists(out)) << "nothing under the final name before commit";
    file.write(std::string("world"));
    file.commit();
  }
  EXPECT_EQ(read(out), "hello world");
  EXPECT_EQ(entries(), 1u) << "no temporary left behind";
}

TEST_F(AtomicFileTest, UncommittedFileLeavesNothing) {
  const fs::path out = dir_ / "frame_0002.ply";
  {
    AtomicFile file(out.string());
    file.write(std::string("partial"));
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(entries(), 0u);
}

TEST_F(AtomicFileTest, CommitReplacesAnOlderFileInOneStep) {
  const fs::path out = dir_ / "manifest.json";
  std::ofstream(out) << "old";
  AtomicFile file(out.string());
  file.write(std::string("new"));
  EXPECT_EQ(read(out), "old");
  file.commit();
  EXPECT_EQ(read(out), "new");
}

TEST_F(AtomicFileTest, UnwritableFolderIsAnOutputErrorNamingTheFile) {
  const fs::path out = dir_ / "missing" / "frame.ply";
  try {
    AtomicFile file(out.string());
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(out.string() + ": cannot create: ", 0), 0u) << e.what();
  }
}

TEST_F(AtomicFileTest, RefuseDifferentKeepsAnEqualFileAndRefusesADifferentOne) {
  const fs::path out = dir_ / "frame_0003.ply";
  std::ofstream(out) << "same";
  {
    AtomicFile file(out.string());
    file.write(std::string("same"));
    EXPECT_EQ(file.commit(Overwrite::kRefuseDifferent), Committed::kUnchanged);
  }
  EXPECT_EQ(read(out), "same");
  EXPECT_EQ(entries(), 1u) << "the temporary of an unchanged file is removed";
  try {
    AtomicFile file(out.string());
    file.write(std::string("other"));
    file.commit(Overwrite::kRefuseDifferent);
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()), out.string() + ": exists with different contents; not overwritten");
  }
  EXPECT_EQ(read(out), "same");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(AtomicFileTest, HandedOverTemporaryIsCommittedByName) {
  const fs::path out = dir_ / "vat_positions.exr";
  AtomicFile file(out.string());
  const std::string temporary = file.hand_over();
  EXPECT_NE(temporary, out.string());
  std::ofstream(temporary, std::ios::binary) << "written by another library";
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(file.commit(), Committed::kWritten);
  EXPECT_EQ(read(out), "written by another library");
  EXPECT_EQ(entries(), 1u);
}

}  // namespace
}  // namespace dqskin
