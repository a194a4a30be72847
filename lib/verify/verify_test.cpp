// dqskin verify and merge through the library on bakes of a bundled rig (deformed on the CPU, so no GL
// context is needed): shards merge into the unsharded bake byte for byte, and every way a folder can
// differ from its manifests is named.
#include "dqskin/verify.hpp"

#include "dqskin/bake.hpp"
#include "dqskin/error.hpp"
#include "../test_support/read_file.hpp"
#include "../test_support/scratch_dir.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using testing_support::read_file;

const unsigned kFormats = unsigned(BakeFormat::kGlb) | unsigned(BakeFormat::kVat) | unsigned(BakeFormat::kBones) |
                          unsigned(BakeFormat::kMorph);

// Every file under `dir`, relative path → bytes.
std::map<std::string, std::string> tree(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out[fs::relative(e.path(), dir).generic_string()] = read_file(e.path());
  return out;
}

std::vector<std::string> kinds(const VerifyReport& r) {
  std::vector<std::string> out;
  for (const FolderProblem& p : r.problems) out.push_back(p.kind + " " + p.path);
  return out;
}

class VerifyTest : public testing::Test {
protected:
  void bake_into(const std::string& folder, Shard shard = {}, BlendMode mode = BlendMode::kDqs) {
    BakeOptions o;
    o.plan.out_dir = (root_ / folder).string();
    o.formats = kFormats;
    o.backend = Backend::kFastCpu;
    o.mode = mode;
    o.jobs = 2;
    o.plan.shard = shard;
    o.plan.frames.fps = 10;
    ASSERT_FALSE(bake({rig_}, o).any_failed());
  }
  std::string at(const std::string& folder) const { return (root_ / folder).string(); }

  const testing_support::ScratchDir scratch_{"verify"};
  const fs::path root_ = scratch_.path();
  const std::string rig_ = std::string(DQSKIN_TESTDATA_DIR) + "/bending_arm.gltf";
};

TEST_F(VerifyTest, ShardsMergeIntoTheUnshardedBake) {
  bake_into("whole");
  for (size_t i = 0; i < 3; ++i) bake_into("sharded", {i, 3});
  const VerifyReport before = verify_folder(at("sharded"));
  EXPECT_TRUE(before.ok()) << testing::PrintToString(kinds(before));
  EXPECT_EQ(before.manifests.size(), 3u);

  const MergeReport merged = merge_shards(at("sharded"));
  ASSERT_TRUE(merged.ok()) << testing::PrintToString(merged.refusals);
  ASSERT_EQ(merged.merged.size(), 1u);
  EXPECT_EQ(merged.merged[0].manifest, "manifest.json");
  EXPECT_EQ(merged.merged[0].shards, 3u);
  EXPECT_EQ(read_file(root_ / "sharded" / "manifest.json"), read_file(root_ / "whole" / "manifest.json"));
  EXPECT_TRUE(tree(root_ / "sharded") == tree(root_ / "whole")) << "the shard manifests are gone, the rest is the bake";
  const VerifyReport after = verify_folder(at("sharded"));
  EXPECT_TRUE(after.ok());
  EXPECT_EQ(after.files, before.files);
  EXPECT_TRUE(merge_shards(at("sharded")).ok()) << "merging a merged folder again changes nothing";
  EXPECT_TRUE(tree(root_ / "sharded") == tree(root_ / "whole"));
}

TEST_F(VerifyTest, AnUnfinishedShardIsNamedAndNothingIsMerged) {
  bake_into("sharded", {0, 3});
  bake_into("sharded", {2, 3});
  const auto before = tree(root_ / "sharded");
  const VerifyReport v = verify_folder(at("sharded"));
  ASSERT_FALSE(v.problems.empty());
  EXPECT_EQ(v.problems.front().kind, "shard-missing");
  EXPECT_EQ(v.problems.front().path, "manifest.shard-1-of-3.json");
  const MergeReport m = merge_shards(at("sharded"));
  EXPECT_FALSE(m.ok());
  EXPECT_TRUE(m.merged.empty());
  EXPECT_TRUE(tree(root_ / "sharded") == before) << "a refused merge writes and deletes nothing";
}

// Consecutive shards missing are one problem: what verify reports grows with the manifests there, not with
// the count their names declare (manifest.shard-0-of-999999.json alone was 999,998 lines).
TEST_F(VerifyTest, ConsecutiveMissingShardsAreOneProblem) {
  bake_into("sharded", {0, 5});
  bake_into("sharded", {3, 5});
  std::vector<std::string> missing;
  for (const FolderProblem& p : verify_folder(at("sharded")).problems)
    if (p.kind == "shard-missing") missing.push_back(p.path + ": " + p.message);
  const std::vector<std::string> expected = {
      "manifest.shard-1-of-5.json: missing, and so are the manifests up to manifest.shard-2-of-5.json: shards 1 to 2 of "
      "5 did not finish (run them again; a shard all of whose inputs fail writes none)",
      "manifest.shard-4-of-5.json: missing: shard 4/5 did not finish (run it again; a shard all of whose inputs fail "
      "writes none)",
  };
  EXPECT_EQ(missing, expected);
}

TEST_F(VerifyTest, ShardsRunWithOtherFlagsAreRefused) {
  bake_into("sharded", {0, 2});
  bake_into("sharded", {1, 2}, BlendMode::kLbs);
  EXPECT_TRUE(verify_folder(at("sharded")).ok()) << "each shard's files are as its manifest says";
  const MergeReport m = merge_shards(at("sharded"));
  ASSERT_EQ(m.refusals.size(), 1u);
  EXPECT_NE(m.refusals[0].find("manifest.shard-1-of-2.json"), std::string::npos) << m.refusals[0];
  EXPECT_NE(m.refusals[0].find("(mode: \"lbs\" here, \"dqs\" there)"), std::string::npos) << m.refusals[0];
  EXPECT_FALSE(fs::exists(root_ / "sharded" / "manifest.json"));
}

TEST_F(VerifyTest, NamesEachWayAFolderDiffersFromItsManifest) {
  bake_into("out");
  ASSERT_TRUE(verify_folder(at("out")).ok());
  const fs::path clip = root_ / "out" / "bending_arm" / "bend";
  ASSERT_TRUE(fs::exists(clip / "frame_0003.glb"));
  {
    std::fstream f(clip / "frame_0001.glb", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(100);
    f.put('\xff');
  }
  fs::resize_file(clip / "frame_0002.glb", 50);
  fs::remove(clip / "frame_0003.glb");
  std::ofstream(clip / "notes.txt") << "extra";
  std::ofstream(clip / ".frame_0004.glb.tmp-4242-0") << "partial";
  std::ofstream(root_ / "out" / ".manifest.json.tmp-4242-1") << "partial";
  const VerifyReport r = verify_folder(at("out"), 2);
  const std::vector<std::string> expected = {
      "temporary .manifest.json.tmp-4242-1",
      "temporary bending_arm/bend/.frame_0004.glb.tmp-4242-0",
      "hash bending_arm/bend/frame_0001.glb",
      "size bending_arm/bend/frame_0002.glb",
      "missing bending_arm/bend/frame_0003.glb",
      "unlisted bending_arm/bend/notes.txt",
  };
  EXPECT_EQ(kinds(r), expected);
  EXPECT_NE(r.problems[3].message.find("50 bytes"), std::string::npos) << r.problems[3].message;
  const auto json = nlohmann::json::parse(verify_json(r));
  EXPECT_FALSE(json["ok"].get<bool>());
  EXPECT_EQ(json["problems"].size(), expected.size());
}

// A manifest is data from elsewhere: a path out of the folder is a problem, never a file read.
TEST_F(VerifyTest, AManifestCannotPointOutOfItsFolder) {
  bake_into("out");
  const fs::path manifest = root_ / "out" / "manifest.json";
  auto json = nlohmann::json::parse(read_file(manifest));
  json["outputs"][0]["path"] = "../whole/secret";
  std::ofstream(manifest) << json.dump();
  const VerifyReport r = verify_folder(at("out"));
  ASSERT_FALSE(r.problems.empty());
  EXPECT_EQ(r.problems[0].kind, "manifest");
  EXPECT_NE(r.problems[0].message.find("outside the folder"), std::string::npos) << r.problems[0].message;
  std::ofstream(manifest) << "{ not json";
  EXPECT_EQ(verify_folder(at("out")).problems[0].message, "the manifest is not valid JSON");
  fs::create_directories(root_ / "empty");
  EXPECT_EQ(verify_folder(at("empty")).problems.at(0).kind, "manifest");
  EXPECT_THROW(verify_folder(at("absent")), InputError);
}

// Manifests are read defensively: one nested without end, one that is a FIFO (opening it would block), one
// that is a link to elsewhere, each a problem line of its own; a broken shard manifest is not also "missing".
TEST_F(VerifyTest, HostileManifestFilesAreProblemsNotCrashesOrHangs) {
  bake_into("sharded", {0, 3});
  bake_into("sharded", {1, 3});
  bake_into("sharded", {2, 3});
  const fs::path folder = root_ / "sharded";
  auto json = nlohmann::json::parse(read_file(folder / "manifest.shard-1-of-3.json"));
  std::string text = json.dump();
  text.pop_back();
  text += ",\"x\":" + std::string(200000, '[') + std::string(200000, ']') + "}";
  std::ofstream(folder / "manifest.shard-1-of-3.json") << text;
  fs::rename(folder / "manifest.shard-2-of-3.json", root_ / "elsewhere.json");
  fs::create_symlink(root_ / "elsewhere.json", folder / "manifest.shard-2-of-3.json");
  ASSERT_EQ(::mkfifo((folder / "render-manifest.json").c_str(), 0644), 0);
  const MergeReport m = merge_shards(at("sharded"));
  EXPECT_FALSE(m.ok());
  std::vector<std::string> manifest_problems;
  for (const FolderProblem& p : m.verify.problems)
    if (p.kind == "manifest" || p.kind == "shard-missing") manifest_problems.push_back(p.kind + " " + p.path + ": " + p.message);
  const std::vector<std::string> expected = {
      "manifest manifest.shard-1-of-3.json: the manifest is nested deeper than 32 levels",
      "manifest manifest.shard-2-of-3.json: the manifest is a symbolic link, which verify does not follow",
      "manifest render-manifest.json: the manifest is not a regular file",
  };
  EXPECT_EQ(manifest_problems, expected);
  EXPECT_TRUE(fs::exists(folder / "manifest.shard-0-of-3.json")) << "a refused merge deletes nothing";
}

// The manifest merge replaces is not consulted, even when it cannot be read (a run killed mid-write of an
// older tool, a copy gone wrong); an input that failed in every shard fails in the merged bake too.
TEST_F(VerifyTest, MergeReplacesAnUnreadableManifestAndKeepsFailedInputs) {
  const std::string missing = (root_ / "missing.gltf").string();
  auto bake_both = [&](const std::string& folder, Shard shard) {
    BakeOptions o;
    o.plan.out_dir = at(folder);
    o.formats = kFormats;
    o.backend = Backend::kFastCpu;
    o.plan.shard = shard;
    o.plan.frames.fps = 10;
    EXPECT_TRUE(bake({rig_, missing}, o).any_failed());
  };
  bake_both("whole", {});
  bake_both("sharded", {0, 2});
  bake_both("sharded", {1, 2});
  std::ofstream(root_ / "sharded" / "manifest.json") << "{\"tool\":";
  const MergeReport m = merge_shards(at("sharded") + "/");
  ASSERT_TRUE(m.ok()) << testing::PrintToString(kinds(m.verify)) << testing::PrintToString(m.refusals);
  EXPECT_EQ(m.verify.folder, at("sharded")) << "named without the trailing slash";
  ASSERT_EQ(m.failed_inputs.size(), 1u);
  EXPECT_EQ(m.failed_inputs[0].first, missing);
  EXPECT_TRUE(tree(root_ / "sharded") == tree(root_ / "whole"));
}

// Links are not followed: an output folder that is a link to elsewhere is named, not walked or read.
TEST_F(VerifyTest, SymbolicLinksAreNotFollowed) {
  bake_into("out");
  fs::rename(root_ / "out" / "bending_arm", root_ / "elsewhere");
  fs::create_directory_symlink(root_ / "elsewhere", root_ / "out" / "bending_arm");
  const VerifyReport r = verify_folder(at("out"));
  ASSERT_FALSE(r.ok());
  for (const FolderProblem& p : r.problems) EXPECT_NE(p.message.find("symbolic link"), std::string::npos) << p.path;
  EXPECT_EQ(r.problems.size(), r.files + 1) << "every listed file, and the folder itself";
}

// A listed path 20,000 folders deep is one file missing, found at once (each of its folders was looked at
// through a copy of its whole path split into parts: verify never returned); an output folder inside
// another is walked with it, so that a file there is named once.
TEST_F(VerifyTest, DeepPathsAndNestedOutputFoldersAreLookedAtOnce) {
  bake_into("out");
  const fs::path manifest = root_ / "out" / "manifest.json";
  auto json = nlohmann::json::parse(read_file(manifest));
  std::string deep = "bending_arm";
  for (int i = 0; i < 20000; ++i) deep += "/a";
  json["outputs"].push_back({{"path", deep + "/f"}, {"size", 0}, {"sha256", std::string(64, '0')}});
  json["inputs"].push_back(json["inputs"][0]);
  json["inputs"][1]["output_folder"] = "bending_arm/bend";
  std::ofstream(manifest) << json.dump();
  std::ofstream(root_ / "out" / "bending_arm" / "bend" / "notes.txt") << "extra";
  const std::vector<std::string> expected = {"missing " + deep + "/f", "unlisted bending_arm/bend/notes.txt"};
  EXPECT_EQ(kinds(verify_folder(at("out"))), expected);
}

// A shard killed mid-bake leaves temporaries; its rerun keeps the finished files and removes them.
TEST_F(VerifyTest, ARerunShardRemovesWhatItsKilledRunLeft) {
  bake_into("sharded", {0, 2});
  bake_into("sharded", {1, 2});
  // A temporary of a file shard 0 writes (the shards' shares are dealt by cost: find one).
  std::string file;
  const nlohmann::json shard0 = nlohmann::json::parse(read_file(root_ / "sharded" / "manifest.shard-0-of-2.json"));
  for (const nlohmann::json& out : shard0["outputs"]) file = out["path"].get<std::string>();
  ASSERT_FALSE(file.empty());
  const fs::path clip = (root_ / "sharded" / file).parent_path();
  const std::string leftover = "." + fs::path(file).filename().string() + ".tmp-1-0";
  std::ofstream(clip / leftover) << "partial";
  fs::remove(root_ / "sharded" / "manifest.shard-0-of-2.json");
  std::ofstream(root_ / "sharded" / ".manifest.shard-0-of-2.json.tmp-1-0") << "{\"partial";  // killed writing it
  EXPECT_FALSE(merge_shards(at("sharded")).ok());
  bake_into("sharded", {0, 2});
  EXPECT_FALSE(fs::exists(clip / leftover));
  EXPECT_FALSE(fs::exists(root_ / "sharded" / ".manifest.shard-0-of-2.json.tmp-1-0"));
  EXPECT_TRUE(merge_shards(at("sharded")).ok());
}

// Textures cut into slices: the merge splices the pieces into the whole bake's files; a shard manifest whose
// pieces name a file outside its outputs (here, outside the folder) is refused, and the folder is left as
// it was.
TEST_F(VerifyTest, MergeSplicesSlicesAndRefusesPiecesOutsideTheOutputs) {
  const std::string rig = std::string(DQSKIN_TESTDATA_DIR) + "/morph_skin.gltf";
  auto bake_shard = [&](const std::string& folder, Shard shard) {
    BakeOptions o;
    o.plan.out_dir = (root_ / folder).string();
    o.formats = unsigned(BakeFormat::kVat) | unsigned(BakeFormat::kBones);
    o.backend = Backend::kFastCpu;
    o.plan.shard = shard;
    ASSERT_FALSE(bake({rig}, o).any_failed());
  };
  bake_shard("whole", {});
  for (const char* folder : {"sharded", "hostile", "no_share", "bad_share"})
    for (size_t i = 0; i < 3; ++i) bake_shard(folder, {i, 3});
  const std::string shard0 = read_file(root_ / "sharded" / "manifest.shard-0-of-3.json");
  ASSERT_NE(shard0.find("\"pieces\""), std::string::npos) << "the textures were cut";
  EXPECT_TRUE(verify_folder(at("sharded")).ok()) << "pieces are outputs like any other";
  ASSERT_TRUE(merge_shards(at("sharded")).ok());
  EXPECT_TRUE(tree(root_ / "sharded") == tree(root_ / "whole"));

  nlohmann::json hostile = nlohmann::json::parse(read_file(root_ / "hostile" / "manifest.shard-0-of-3.json"));
  ASSERT_TRUE(hostile.contains("pieces"));
  hostile["pieces"][0]["path"] = "../escaped.exr.rows-0-16";
  hostile["pieces"][0]["whole"] = "../escaped.exr";
  std::ofstream(root_ / "hostile" / "manifest.shard-0-of-3.json") << hostile.dump();
  const auto before = tree(root_ / "hostile");
  const MergeReport refused = merge_shards(at("hostile"));
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(testing::PrintToString(refused.refusals).find("is not a piece of a file among the shard's outputs"), std::string::npos)
      << testing::PrintToString(refused.refusals);
  EXPECT_TRUE(tree(root_ / "hostile") == before) << "nothing written or deleted";
  EXPECT_FALSE(fs::exists(root_ / "escaped.exr"));

  // The figures: a shard's share missing, or not an object, would leave the merged figures short of the
  // slices; both are refused, naming what is wrong, and the folder is left as it was.
  auto edit_shares = [&](const std::string& folder, const std::function<void(nlohmann::json&)>& edit) {
    for (size_t i = 3; i-- > 1;) {  // the last shard with a share (not the head's, shard 0)
      const fs::path path = root_ / folder / ("manifest.shard-" + std::to_string(i) + "-of-3.json");
      nlohmann::json m = nlohmann::json::parse(read_file(path));
      nlohmann::json& clip = m["inputs"][0]["animations"][0];
      if (clip.contains("decode_check_share")) {
        edit(clip);
        std::ofstream(path) << m.dump();
        return;
      }
    }
    FAIL() << "no shard but the head has a share";
  };
  edit_shares("no_share", [](nlohmann::json& clip) { clip.erase("decode_check_share"); });
  edit_shares("bad_share", [](nlohmann::json& clip) { clip["decode_check_share"] = nlohmann::json::array({1, 2}); });
  for (const char* folder : {"no_share", "bad_share"}) {
    SCOPED_TRACE(folder);
    const auto untouched = tree(root_ / folder);
    const MergeReport r = merge_shards(at(folder));
    ASSERT_FALSE(r.ok());
    const std::string said = testing::PrintToString(r.refusals);
    EXPECT_TRUE(said.find("do not cover its") != std::string::npos || said.find("is not an object") != std::string::npos) << said;
    EXPECT_TRUE(tree(root_ / folder) == untouched) << "nothing written or deleted";
  }
}

}  // namespace
}  // namespace dqskin
