#include "dqskin/animation.hpp"
#include "dqskin/error.hpp"

#include <gtest/gtest.h>

namespace dqskin {
namespace {

Clip clip_with_keys(std::vector<float> times) {
  Clip clip;
  Channel ch;
  ch.times = times;
  ch.components = 3;
  ch.values.assign(times.size() * 3, 0.0f);
  clip.channels.push_back(ch);
  clip.first_key = double(times.front());
  clip.last_key = double(times.back());
  return clip;
}

TEST(FrameTimes, GridRunsFromZeroToTheLastKeyInclusive) {
  const std::vector<double> t = frame_times(clip_with_keys({0.5f, 2.0f}), FrameSpec{});
  ASSERT_EQ(t.size(), 61u);  // 2 s at 30 fps: frames 0..60
  EXPECT_EQ(t.front(), 0.0);
  EXPECT_DOUBLE_EQ(t.back(), 2.0);
}

TEST(FrameTimes, FrameIIsStartPlusIOverFpsNotAnAccumulatedSum) {
  FrameSpec spec;
  spec.fps = 24;
  const std::vector<double> t = frame_times(clip_with_keys({0, 10}), spec);
  for (size_t i = 0; i < t.size(); ++i) EXPECT_EQ(t[i], double(i) / 24) << i;  // exact equality
}

TEST(FrameTimes, FromFirstKeyStartsAtTheFirstKey) {
  FrameSpec spec;
  spec.from_first_key = true;
  const std::vector<double> t = frame_times(clip_with_keys({0.5f, 1.5f}), spec);
  ASSERT_EQ(t.size(), 31u);
  EXPECT_EQ(t.front(), 0.5);
  EXPECT_EQ(t[3], 0.5 + 3.0 / 30);
}

TEST(FrameTimes, DurationThatIsNotAWholeFrameEndsBeforeTheLastKey) {
  // 2.0833 s (RiggedSimple) at 30 fps: frames 0..62, the last at 2.0667 s.
  const std::vector<double> t = frame_times(clip_with_keys({0, 2.0833333f}), FrameSpec{});
  ASSERT_EQ(t.size(), 63u);
  EXPECT_LE(t.back(), 2.0833333);
}

TEST(FrameTimes, RangeSelectsFramesInclusiveWithStep) {
  FrameSpec spec;
  parse_frame_range("10:20:5", spec);
  const std::vector<double> t = frame_times(clip_with_keys({0, 2}), spec);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[0], 10.0 / 30);
  EXPECT_EQ(t[2], 20.0 / 30);
}

TEST(FrameTimes, RangeBeyondTheClipIsAnError) {
  FrameSpec spec;
  parse_frame_range("0:61", spec);
  EXPECT_THROW(frame_times(clip_with_keys({0, 2}), spec), InputError);
}

TEST(FrameTimes, GridFrameCountIsTheGridsLengthWhateverTheRange) {
  FrameSpec spec;
  parse_frame_range("0:59", spec);  // first, last and step do not change the grid
  EXPECT_EQ(grid_frame_count(clip_with_keys({0, 0.4f}), spec), 13);  // 0.4 s at 30 fps: frames 0..12
  EXPECT_EQ(grid_frame_count(clip_with_keys({0, 2}), spec), 61);
  spec.from_first_key = true;
  EXPECT_EQ(grid_frame_count(clip_with_keys({1, 2}), spec), 31);
  spec.fps = 0;
  EXPECT_THROW(grid_frame_count(clip_with_keys({0, 2}), spec), InputError);
}

TEST(FrameTimes, KeysGivesEveryDistinctKeyTimeInOrder) {
  Clip clip = clip_with_keys({0, 1, 2});
  Channel other = clip.channels[0];
  other.times = {0.5f, 1, 3};
  clip.channels.push_back(other);
  FrameSpec spec;
  spec.keys = true;
  EXPECT_EQ(frame_times(clip, spec), (std::vector<double>{0, 0.5, 1, 2, 3}));
}

TEST(FrameTimes, ExplicitTimesAreUsedAsGiven) {
  FrameSpec spec;
  spec.times = parse_times("0,0.5,1.25");
  EXPECT_EQ(frame_times(clip_with_keys({0, 1}), spec), (std::vector<double>{0, 0.5, 1.25}));
}

TEST(FrameTimes, BadSpecificationsAreErrors) {
  FrameSpec spec;
  EXPECT_THROW(parse_frame_range("5", spec), InputError);
  EXPECT_THROW(parse_frame_range("5:2", spec), InputError);
  EXPECT_THROW(parse_frame_range("a:2", spec), InputError);
  EXPECT_THROW(parse_frame_range("0:2:0", spec), InputError);
  EXPECT_THROW(parse_times("0,,1"), InputError);
  EXPECT_THROW(parse_times("-1"), InputError);
  EXPECT_THROW(parse_times("nan"), InputError);
  FrameSpec zero_fps;
  zero_fps.fps = 0;
  EXPECT_THROW(frame_times(clip_with_keys({0, 1}), zero_fps), InputError);
}

TEST(SelectClips, AllNameOrIndex) {
  Asset asset;
  asset.clips.resize(3);
  asset.clips[0].name = "Walk";
  asset.clips[1].name = "2";  // a name that looks like an index wins as a name
  asset.clips[2].name = "Run";
  EXPECT_EQ(select_clips(asset, "all"), (std::vector<size_t>{0, 1, 2}));
  EXPECT_EQ(select_clips(asset, "Run"), (std::vector<size_t>{2}));
  EXPECT_EQ(select_clips(asset, "0"), (std::vector<size_t>{0}));
  EXPECT_EQ(select_clips(asset, "2"), (std::vector<size_t>{1}));
  try {
    select_clips(asset, "Jump");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "no animation 'Jump' (the file has Walk, 2, Run)");
  }
  EXPECT_THROW(select_clips(asset, "3"), InputError);
}

}  // namespace
}  // namespace dqskin
