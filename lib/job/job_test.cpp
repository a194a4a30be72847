// The job layer on the bundled rigs: shards split the plan's units between them exactly once, a failing
// input takes no unit and fails alone, a cancel keeps the files written.
#include "job_plan.hpp"
#include "job_run.hpp"

#include "dqskin/atomic_file.hpp"
#include "dqskin/error.hpp"
#include "../test_support/scratch_dir.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <new>
#include <thread>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using testing_support::ScratchDir;

std::string rig(const char* name) { return std::string(DQSKIN_TESTDATA_DIR) + "/" + name; }

std::vector<InputPlan> plan(const std::vector<std::string>& inputs, Shard shard, const fs::path& out) {
  PlanOptions o;
  o.out_dir = out.string();
  o.frames.fps = 10;
  o.shard = shard;
  double seconds = 0;
  return plan_inputs(inputs, o, seconds);
}

TEST(JobPlan, ClipFoldersStayUniqueWhenAnIndexedNameIsTaken) {
  // Clips "Walk_2", "Walk", "Walk": the third would be "Walk_2" by its index, which the first has.
  ScratchDir out("job");
  std::ifstream in(rig("twisted_cylinder.gltf"));
  nlohmann::json doc = nlohmann::json::parse(in);
  const nlohmann::json clip = doc["animations"][0];
  doc["animations"] = nlohmann::json::array();
  for (const char* name : {"Walk_2", "Walk", "Walk"}) {
    doc["animations"].push_back(clip);
    doc["animations"].back()["name"] = name;
  }
  const fs::path file = out.path() / "walks.gltf";
  std::ofstream(file) << doc.dump();
  const std::vector<InputPlan> plans = plan({file.string()}, {}, out.path());
  ASSERT_EQ(plans.size(), 1u);
  ASSERT_EQ(plans[0].error, "");
  ASSERT_EQ(plans[0].clips.size(), 3u);
  EXPECT_EQ(plans[0].clips[0].folder, "walks/Walk_2");
  EXPECT_EQ(plans[0].clips[1].folder, "walks/Walk");
  EXPECT_EQ(plans[0].clips[2].folder, "walks/Walk_2_2");
}

TEST(ParseShard, AcceptsIOfNAndRejectsTheRest) {
  const Shard s = parse_shard("2/5");
  EXPECT_EQ(s.index, 2u);
  EXPECT_EQ(s.count, 5u);
  for (const char* bad : {"5/5", "1/0", "1", "a/2", "-1/2", "1/2/3", "", "1234567/9999999"})
    EXPECT_THROW(parse_shard(bad), InputError) << bad;
}

TEST(JobPlan, ShardsOwnEveryFrameAndClipExactlyOnce) {
  ScratchDir out("job");
  const std::vector<std::string> inputs = {rig("bending_arm.gltf"), rig("two_skins.gltf"), rig("twisted_cylinder.gltf"),
                                            rig("interpolation_modes.gltf")};
  const std::vector<InputPlan> whole = plan(inputs, {}, out.path());
  size_t frames = 0, clips = 0;
  for (const InputPlan& p : whole) {
    ASSERT_EQ(p.error, "") << p.path;
    for (const ClipPlan& c : p.clips) {
      EXPECT_TRUE(c.clip_mine);
      EXPECT_EQ(c.my_frames().size(), c.times.size());
      frames += c.times.size(), ++clips;
    }
  }
  ASSERT_GT(clips, 3u);  // more clips than shards: every shard gets some
  std::vector<std::vector<int>> frame_owners;  // per input, clip, frame: how many shards own it
  size_t clip_owners = 0, frame_owned = 0;
  for (size_t i = 0; i < 3; ++i) {
    const std::vector<InputPlan> part = plan(inputs, {i, 3}, out.path());
    size_t mine = 0;
    for (size_t p = 0; p < part.size(); ++p)
      for (size_t c = 0; c < part[p].clips.size(); ++c) {
        const ClipPlan& clip = part[p].clips[c];
        EXPECT_EQ(clip.times, whole[p].clips[c].times);  // every shard plans the same frames
        EXPECT_EQ(clip.folder, whole[p].clips[c].folder);
        clip_owners += clip.clip_mine;
        mine += clip.my_frames().size();
      }
    EXPECT_GT(mine, 0u) << "shard " << i;
    frame_owned += mine;
  }
  EXPECT_EQ(clip_owners, clips);
  EXPECT_EQ(frame_owned, frames);
}

TEST(JobPlan, AFailingInputTakesNoUnits) {
  ScratchDir out("job");
  const std::vector<InputPlan> alone = plan({rig("bending_arm.gltf")}, {1, 2}, out.path());
  const std::vector<InputPlan> after = plan({rig("missing.gltf"), rig("bending_arm.gltf")}, {1, 2}, out.path());
  ASSERT_EQ(after.size(), 2u);
  EXPECT_NE(after[0].error, "");
  EXPECT_TRUE(after[0].clips.empty());
  ASSERT_EQ(after[1].clips.size(), alone[0].clips.size());
  for (size_t c = 0; c < alone[0].clips.size(); ++c) {
    EXPECT_EQ(after[1].clips[c].frame_mine, alone[0].clips[c].frame_mine);
    EXPECT_EQ(after[1].clips[c].clip_mine, alone[0].clips[c].clip_mine);
  }
}

TEST(JobPlan, TwoInputsWritingOneFolderAreRefused) {
  ScratchDir out("job");
  EXPECT_THROW(plan({rig("bending_arm.gltf"), rig("bending_arm.gltf")}, {}, out.path()), InputError);
}

// Writes <out>/<stem>/file.txt through the journal.
void write_one(const fs::path& out, const InputPlan& input, OutputJournal& journal) {
  journal.make_folders((out / input.stem).string());
  AtomicFile file((out / input.stem / "file.txt").string(), false);
  file.write(input.path);
  file.commit({Overwrite::kReplace, &journal});
}

TEST(JobRun, AFailingInputIsTakenBackAndTheOthersGoOn) {
  ScratchDir out("job");
  const std::vector<InputPlan> plans =
      plan({rig("missing.gltf"), rig("bending_arm.gltf"), rig("two_skins.gltf")}, {}, out.path());
  std::vector<std::string> forgotten;
  const std::vector<InputResult> results = for_each_input(
      plans,
      [&](const InputPlan& input, OutputJournal& journal, InputResult& result) {
        write_one(out.path(), input, journal);
        result.frames = 7;
        if (input.stem == "bending_arm") throw OutputError("disk full");
      },
      [&](const InputPlan& input) { forgotten.push_back(input.stem); });
  ASSERT_EQ(results.size(), 3u);
  EXPECT_NE(results[0].error, "");                  // the plan's own error; work never ran
  EXPECT_EQ(results[1].error, "disk full");
  EXPECT_EQ(results[1].frames, 0u);  // its outputs were taken back
  EXPECT_EQ(results[2].error, "");
  EXPECT_EQ(results[2].frames, 7u);
  EXPECT_EQ(forgotten, std::vector<std::string>{"bending_arm"});
  EXPECT_FALSE(fs::exists(out.path() / "bending_arm"));  // its folder and file taken back
  EXPECT_TRUE(fs::exists(out.path() / "two_skins" / "file.txt"));
}

TEST(JobRun, ACancelLeavesTheLoopAndKeepsTheFiles) {
  ScratchDir out("job");
  const std::vector<InputPlan> plans = plan({rig("bending_arm.gltf"), rig("two_skins.gltf")}, {}, out.path());
  size_t started = 0;
  EXPECT_THROW(for_each_input(
                   plans,
                   [&](const InputPlan& input, OutputJournal& journal, InputResult&) {
                     ++started;
                     write_one(out.path(), input, journal);
                     throw JobCancelled();
                   },
                   [](const InputPlan&) { FAIL() << "a cancelled input is not a failed one"; }),
               JobCancelled);
  EXPECT_EQ(started, 1u);
  EXPECT_TRUE(fs::exists(out.path() / "bending_arm" / "file.txt"));
}

TEST(JobRun, OutOfMemoryFailsTheInputAndNoContextStopsTheJob) {
  ScratchDir out("job");
  const std::vector<InputPlan> plans = plan({rig("bending_arm.gltf"), rig("two_skins.gltf")}, {}, out.path());
  const std::vector<InputResult> results = for_each_input(
      plans,
      [](const InputPlan& input, OutputJournal&, InputResult&) {
        if (input.stem == "bending_arm") throw std::bad_alloc();
      },
      [](const InputPlan&) {});
  EXPECT_EQ(results[0].error, kOutOfMemory);
  EXPECT_EQ(results[1].error, "");

  size_t started = 0;
  EXPECT_THROW(for_each_input(
                   plans,
                   [&](const InputPlan&, OutputJournal&, InputResult&) {
                     ++started;
                     throw NoGpuContext("no OpenGL 4.3 core context: test");
                   },
                   [](const InputPlan&) { FAIL() << "no context is not an input's failure"; }),
               NoGpuContext);
  EXPECT_EQ(started, 1u);
}

// Writers on several threads report frames at once: every frame is counted once, the total is the job's.
TEST(ProgressCounter, CountsEveryFrameOnceAcrossThreads) {
  std::mutex mutex;
  std::vector<size_t> seen;
  ProgressCounter counter(1000, [&](const JobProgress& p) {
    EXPECT_EQ(p.frames_total, 1000u);
    const std::lock_guard<std::mutex> lock(mutex);
    seen.push_back(p.frames_done);
  });
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&] {
      for (int i = 0; i < 250; ++i) counter.add(1, "in.gltf", "walk");
    });
  for (std::thread& t : threads) t.join();
  ASSERT_EQ(seen.size(), 1000u);
  std::sort(seen.begin(), seen.end());
  for (size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], i + 1);  // each count reported exactly once
}

TEST(CheckCancelled, ThrowsOnceTheFlagIsSet) {
  std::atomic<bool> cancel{false};
  EXPECT_NO_THROW(check_cancelled(nullptr));
  EXPECT_NO_THROW(check_cancelled(&cancel));
  cancel = true;
  EXPECT_THROW(check_cancelled(&cancel), JobCancelled);
}

}  // namespace
}  // namespace dqskin
