#include "dqskin/diff_report.hpp"
#include "dqskin/error.hpp"
#include "dqskin/image_diff.hpp"
#include "../test_support/scratch_dir.hpp"
#include "../test_support/read_file.hpp"
#include "../test_support/image_diff_fixture_oiio.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kInf = std::numeric_limits<double>::infinity();

using testing_support::read_file;

DiffOptions thresholds(double fail, double warn) {
  DiffOptions o;
  o.thresholds.fail = fail;
  o.thresholds.warn = warn;
  return o;
}

TEST_F(ImageDiffTest, IdenticalImagesPassWithZeroErrorAndInfinitePsnr) {
  const std::string a = image("a.png", 4, 4, 3, 0.5f), b = image("b.png", 4, 4, 3, 0.5f);
  const DiffReport r = diff_images(a, b, {});
  ASSERT_EQ(r.pairs.size(), 1u);
  const ImageDiff& d = r.pairs[0];
  EXPECT_EQ(d.status, DiffStatus::kPass);
  EXPECT_TRUE(d.compared);
  EXPECT_EQ(d.name, a);
  EXPECT_EQ(d.max_error, 0.0);
  EXPECT_EQ(d.mean_error, 0.0);
  EXPECT_EQ(d.rms_error, 0.0);
  EXPECT_TRUE(std::isinf(d.psnr) && d.psnr > 0);
  EXPECT_EQ(d.pixels, 16u);
  EXPECT_EQ(d.over_warn, 0u);
  EXPECT_EQ(d.over_fail, 0u);
  EXPECT_EQ(d.reason, "");
  EXPECT_EQ(r.status(), DiffStatus::kPass);
}

TEST_F(ImageDiffTest, DefaultThresholdsFailAnyDifferenceAsIdiffDoes) {
  // One 8-bit step (1/255) in one channel of one pixel: over idiff's default 1e-6.
  const std::string a = image("a.png", 4, 4, 3, 0.5f);
  const std::string b = image("b.png", 4, 4, 3, 0.5f, {{5, 1, 0.5f + 1.0f / 255}});
  const ImageDiff d = diff_images(a, b, {}).pairs.at(0);
  EXPECT_EQ(d.status, DiffStatus::kFail);
  EXPECT_EQ(d.over_fail, 1u);
  EXPECT_EQ(d.over_warn, 1u);
  EXPECT_EQ(d.max_x, 1);
  EXPECT_EQ(d.max_y, 1);
  EXPECT_EQ(d.max_channel, "G");
  EXPECT_NEAR(d.max_error, 1.0 / 255, 1e-6);
  EXPECT_EQ(d.reason, "1 pixel (6.25%) over --fail 1e-06, more than --failpercent 0");
}

TEST_F(ImageDiffTest, SlightlyDifferentImagesWarnBetweenWarnAndFail) {
  const std::string a = image("a.exr", 4, 4, 4, 0.25f);
  const std::string b = image("b.exr", 4, 4, 4, 0.25f, {{0, 0, 0.3f}, {15, 3, 0.27f}});
  const ImageDiff d = diff_images(a, b, thresholds(0.1, 0.01)).pairs.at(0);
  EXPECT_EQ(d.status, DiffStatus::kWarn);
  EXPECT_EQ(d.over_warn, 2u);
  EXPECT_EQ(d.over_fail, 0u);
  EXPECT_NEAR(d.max_error, 0.05, 1e-6);
  EXPECT_EQ(d.max_channel, "R");
  EXPECT_EQ(d.reason, "2 pixels (12.5%) over --warn 0.01, more than --warnpercent 0");
}

TEST_F(ImageDiffTest, VeryDifferentImagesFail) {
  const std::string a = image("a.png", 8, 8, 3, 0.0f), b = image("b.png", 8, 8, 3, 1.0f);
  const ImageDiff d = diff_images(a, b, thresholds(0.1, 0.01)).pairs.at(0);
  EXPECT_EQ(d.status, DiffStatus::kFail);
  EXPECT_EQ(d.max_error, 1.0);
  EXPECT_EQ(d.mean_error, 1.0);
  EXPECT_EQ(d.over_fail, 64u);
  EXPECT_EQ(d.psnr, 0.0);  // 20 log10(1 / 1)
}

TEST_F(ImageDiffTest, FailPercentAllowsSomePixelsOverFailThenWarns) {
  const std::string a = image("a.exr", 4, 4, 1, 0.0f), b = image("b.exr", 4, 4, 1, 0.0f, {{3, 0, 1.0f}});
  DiffOptions o;
  o.thresholds.fail_percent = 10;  // 1 of 16 is 6.25 %
  EXPECT_EQ(diff_images(a, b, o).pairs.at(0).status, DiffStatus::kWarn);
  o.thresholds.warn_percent = 10;
  EXPECT_EQ(diff_images(a, b, o).pairs.at(0).status, DiffStatus::kPass);
  o.thresholds.hard_warn = 0.5;
  EXPECT_EQ(diff_images(a, b, o).pairs.at(0).reason, "max error 1 over --hardwarn 0.5");
  o.thresholds.hard_fail = 0.5;
  const ImageDiff d = diff_images(a, b, o).pairs.at(0);
  EXPECT_EQ(d.status, DiffStatus::kFail);
  EXPECT_EQ(d.reason, "max error 1 over --hardfail 0.5");
}

TEST(ImageDiffVerdict, FollowsIdiffRules) {
  DiffThresholds t;
  t.fail_percent = 10;
  t.warn_percent = 5;
  t.hard_fail = 0.9;
  t.hard_warn = 0.5;
  // (max error, over warn, over fail) of 100 pixels → status
  EXPECT_EQ(diff_verdict(t, 0.0, 0, 0, 100), DiffStatus::kPass);
  EXPECT_EQ(diff_verdict(t, 0.1, 5, 5, 100), DiffStatus::kPass);    // at the percentages, not over them
  EXPECT_EQ(diff_verdict(t, 0.1, 6, 5, 100), DiffStatus::kWarn);    // more than warn_percent
  EXPECT_EQ(diff_verdict(t, 0.6, 0, 0, 100), DiffStatus::kWarn);    // over hard_warn
  EXPECT_EQ(diff_verdict(t, 0.1, 11, 11, 100), DiffStatus::kFail);  // more than fail_percent
  EXPECT_EQ(diff_verdict(t, 0.95, 0, 0, 100), DiffStatus::kFail);   // over hard_fail
  EXPECT_EQ(diff_verdict(t, kInf, 0, 0, 100), DiffStatus::kFail);   // not finite
  EXPECT_EQ(diff_verdict(t, std::nan(""), 0, 0, 100), DiffStatus::kFail);
  // Warnings are judged even when no pixel is over --fail (idiff 2.4's --allowfailures short cut does not).
  EXPECT_EQ(diff_verdict(DiffThresholds{0.5, 0, kInf, 0.01, 0, kInf}, 0.1, 1, 0, 100), DiffStatus::kWarn);
}

TEST(ImageDiffThresholds, RejectsNegativeNanAndPercentOutOfRange) {
  EXPECT_EQ(check_thresholds({}), "");
  EXPECT_EQ(check_thresholds({0, 100, kInf, 0, 0, kInf}), "");
  EXPECT_EQ(check_thresholds({-1, 0, kInf, 0, 0, kInf}), "--fail must be at least 0, not -1");
  EXPECT_EQ(check_thresholds({0, 0, kInf, std::nan(""), 0, kInf}), "--warn must be at least 0, not nan");
  EXPECT_EQ(check_thresholds({0, 0, -kInf, 0, 0, kInf}), "--hardfail must be at least 0, not -inf");
  EXPECT_EQ(check_thresholds({0, 101, kInf, 0, 0, kInf}), "--failpercent must be from 0 to 100, not 101");
  EXPECT_EQ(check_thresholds({0, 0, kInf, 0, -0.5, kInf}), "--warnpercent must be from 0 to 100, not -0.5");
}

TEST_F(ImageDiffTest, SizeAndChannelMismatchFailWithoutMetrics) {
  const std::string a = image("a.png", 8, 4, 3, 0.5f);
  const ImageDiff size = diff_images(a, image("b.png", 4, 4, 3, 0.5f), {}).pairs.at(0);
  EXPECT_EQ(size.status, DiffStatus::kFail);
  EXPECT_FALSE(size.compared);
  EXPECT_EQ(size.problem, "size 8x4 vs 4x4");
  EXPECT_EQ(size.unreadable, "");
  const ImageDiff channels = diff_images(a, image("c.png", 8, 4, 4, 0.5f), {}).pairs.at(0);
  EXPECT_EQ(channels.status, DiffStatus::kFail);
  EXPECT_EQ(channels.problem, "3 channels vs 4");
}

TEST_F(ImageDiffTest, UnreadableAndMissingFilesFailNamingTheFile) {
  const std::string good = image("good.png", 2, 2, 3, 0.5f);
  const std::string bad = text_file("bad.png", "this is not a PNG file\n");
  const ImageDiff d = diff_images(good, bad, {}).pairs.at(0);
  EXPECT_EQ(d.status, DiffStatus::kFail);
  EXPECT_FALSE(d.compared);
  EXPECT_EQ(d.unreadable, bad);
  EXPECT_EQ(d.problem.rfind("cannot read " + bad + ": ", 0), 0u) << d.problem;
  EXPECT_EQ(d.problem.find('\n'), std::string::npos);

  const ImageDiff none = diff_images(path("none.png"), good, {}).pairs.at(0);
  EXPECT_EQ(none.unreadable, path("none.png"));
  EXPECT_EQ(none.problem, "cannot read " + path("none.png") + ": No such file or directory");
  EXPECT_EQ(none.read_error, "No such file or directory");

  // Every truncated prefix of an image is refused with a message, or read whole when only bytes after the
  // pixels are lost; never read past its end (the sanitizers watch). EXR, not PNG: OpenImageIO 2.4's PNG
  // reader leaks its error message when libpng stops mid-file (png_chunk_error longjmps past a
  // std::string), which LeakSanitizer would report against this test.
  const std::string bytes = read_file(image("whole.exr", 3, 3, 3, 0.25f));
  const std::string same = image("same.exr", 3, 3, 3, 0.25f);
  for (size_t n = 0; n < bytes.size(); n += 3) {
    const std::string cut = text_file("cut.exr", bytes.substr(0, n));
    const ImageDiff t = diff_images(same, cut, {}).pairs.at(0);
    if (t.compared) {
      EXPECT_EQ(t.status, DiffStatus::kPass) << n;
    } else {
      EXPECT_EQ(t.status, DiffStatus::kFail) << n;
      EXPECT_EQ(t.unreadable, cut) << n << ": " << t.problem;
    }
  }
}

TEST_F(ImageDiffTest, NanOnOneSideFailsAndNanOnBothSidesMatches) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::string a = image("a.exr", 2, 2, 1, 0.0f), b = image("b.exr", 2, 2, 1, 0.0f, {{2, 0, nan}});
  const ImageDiff one = diff_images(a, b, thresholds(0.5, 0.5)).pairs.at(0);
  EXPECT_EQ(one.status, DiffStatus::kFail);
  EXPECT_FALSE(std::isfinite(one.max_error));
  EXPECT_EQ(diff_images(b, b, {}).pairs.at(0).status, DiffStatus::kPass);
}

TEST_F(ImageDiffTest, FoldersPairByRelativePathRecursivelyAndIgnoreOtherFiles) {
  image("A/x.png", 2, 2, 3, 0.5f);
  image("B/x.png", 2, 2, 3, 0.5f);
  image("A/sub/y.exr", 2, 2, 3, 0.5f);
  image("B/sub/y.exr", 2, 2, 3, 0.5f);
  image("A/only_a.PNG", 2, 2, 3, 0.5f);
  image("B/sub/only_b.jpg", 2, 2, 3, 0.5f);
  text_file("A/manifest.json", "{}");
  text_file("B/notes.txt", "");
  const std::vector<DiffPair> pairs = pair_inputs(path("A"), path("B"));
  ASSERT_EQ(pairs.size(), 4u);
  EXPECT_EQ(pairs[0].name, "only_a.PNG");
  EXPECT_EQ(pairs[0].b, "");
  EXPECT_EQ(pairs[1].name, "sub/only_b.jpg");
  EXPECT_EQ(pairs[1].a, "");
  EXPECT_EQ(pairs[2].name, "sub/y.exr");
  EXPECT_EQ(pairs[2].a, path("A/sub/y.exr"));
  EXPECT_EQ(pairs[2].b, path("B/sub/y.exr"));
  EXPECT_EQ(pairs[2].heat_map_name, "sub/y.exr.diff.png");
  EXPECT_EQ(pairs[3].name, "x.png");

  const DiffReport r = diff_images(path("A"), path("B"), {});
  EXPECT_EQ(r.pairs[0].problem, "missing in B, only in A");
  EXPECT_EQ(r.pairs[1].problem, "missing in A, only in B");
  EXPECT_EQ(r.count(DiffStatus::kPass), 2u);
  EXPECT_EQ(r.count(DiffStatus::kFail), 2u);
  EXPECT_EQ(r.status(), DiffStatus::kFail);
}

// A folder whose pairs pass, warn, fail, differ in size, are missing or unreadable, some of them FLIP's by
// a rule: compared several at once (threads), under a budget that holds one pair but not two, the report
// and the heat maps are those of one pair at a time.
TEST_F(ImageDiffTest, PairsComparedAtOnceGiveTheReportOfOneAtATime) {
  for (int i = 0; i < 12; ++i) {
    const std::string name = "p" + std::to_string(10 + i) + ".png";
    image("A/" + name, 64, 48, 3, 0.5f);
    if (i % 6 == 1) continue;  // missing in B
    if (i % 6 == 2) {
      image("B/" + name, 32, 48, 3, 0.5f);  // another size
    } else if (i % 6 == 3) {
      text_file("B/" + name, "not a PNG");
    } else {
      image("B/" + name, 64, 48, 3, 0.5f, {{i * 37, 0, i % 6 == 4 ? 0.9f : 0.51f}, {i * 50, 2, 0.2f}});
    }
  }
  DiffOptions o;
  o.thresholds.fail = 0.1, o.thresholds.warn = 0.001;
  DiffRule flip;
  flip.pattern = "p2?.png";
  flip.metric = DiffMetric::kFlip;
  flip.thresholds = flip_thresholds({}, {});
  o.rules = {flip};
  const auto run = [&](unsigned threads, uint64_t budget, const std::string& out) {
    DiffOptions t = o;
    t.threads = threads;
    t.max_memory = budget;
    t.heat_map_dir = path(out);
    std::string text = diff_json(diff_images(path("A"), path("B"), t));
    for (size_t at; (at = text.find(t.heat_map_dir)) != std::string::npos;) text.replace(at, t.heat_map_dir.size(), "OUT");
    return text;
  };
  const std::string one = run(1, kDefaultMaxMemory, "one");
  EXPECT_EQ(nlohmann::json::parse(one)["pairs"].size(), 12u);
  EXPECT_EQ(run(4, kDefaultMaxMemory, "four"), one);
  EXPECT_EQ(run(4, 2 << 20, "tight"), one);  // one FLIP pair (about 1.3 MiB at 64x48) at a time, not two
  for (const fs::directory_entry& e : fs::directory_iterator(dir_ / "one")) {
    const std::string name = e.path().filename().string();
    EXPECT_EQ(testing_support::read_file((dir_ / "four" / name).string()), testing_support::read_file(e.path().string())) << name;
    EXPECT_EQ(testing_support::read_file((dir_ / "tight" / name).string()), testing_support::read_file(e.path().string())) << name;
  }
}

// An error (not a failing pair) stops the diff; compared at once, it is still the first pair's in name order.
TEST_F(ImageDiffTest, TheErrorOfPairsComparedAtOnceIsTheFirstInNameOrder) {
  for (const char* name : {"a", "b", "c", "d", "e", "f", "g", "h"}) {
    image(std::string("A/") + name + ".png", 64, 64, 3, 0.5f);
    image(std::string("B/") + name + ".png", 64, 64, 3, 0.5f);
  }
  const std::string small = image("small.png", 2, 2, 1, 1.0f);
  DiffOptions o;
  o.threads = 4;
  for (const char* pattern : {"f.png", "c.png"}) {
    DiffRule rule;
    rule.pattern = pattern;
    rule.thresholds = o.thresholds;
    rule.mask.images = {small};
    o.rules.push_back(rule);
  }
  for (int run = 0; run < 10; ++run) {
    try {
      diff_images(path("A"), path("B"), o);
      ADD_FAILURE() << "no exception";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), small + ": the mask is 2x2, the images 64x64");
    }
  }
}

TEST_F(ImageDiffTest, ImageAndFolderCompareWithTheSameNameAsIdiffDoes) {
  const std::string a = image("a/frame.png", 2, 2, 3, 0.5f);
  image("b/frame.png", 2, 2, 3, 0.5f);
  const std::vector<DiffPair> pairs = pair_inputs(a, path("b"));
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0].b, path("b/frame.png"));
  EXPECT_EQ(pairs[0].heat_map_name, "frame.png.diff.png");
}

TEST_F(ImageDiffTest, FolderAgainstImageAndEmptyFoldersAreInputErrors) {
  const std::string a = image("a/frame.png", 2, 2, 3, 0.5f);
  EXPECT_THROW(pair_inputs(path("a"), a), InputError);
  fs::create_directories(dir_ / "e1");
  fs::create_directories(dir_ / "e2");
  text_file("e2/readme.txt", "");
  try {
    pair_inputs(path("e1"), path("e2"));
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path("e1") + ": no image files here or in " + path("e2"));
  }
}

TEST(ImageDiffNames, ImageExtensionsAreCaseInsensitive) {
  EXPECT_TRUE(is_image_name("a/b/frame_0001.png"));
  EXPECT_TRUE(is_image_name("X.EXR"));
  EXPECT_TRUE(is_image_name("x.JpEg"));
  EXPECT_TRUE(is_image_name("x.tiff"));
  EXPECT_FALSE(is_image_name("manifest.json"));
  EXPECT_FALSE(is_image_name("png"));
  EXPECT_FALSE(is_image_name("folder.png/file"));
  EXPECT_FALSE(is_image_name(".x.png.tmp-12-0"));
  EXPECT_FALSE(is_image_name("movie.mp4"));
}

TEST_F(ImageDiffTest, HeatMapIsWrittenForFailingPairsOnlyAndIsDeterministic) {
  image("A/same.png", 4, 2, 3, 0.5f);
  image("B/same.png", 4, 2, 3, 0.5f);
  image("A/sub/warn.exr", 4, 2, 3, 0.5f);
  image("B/sub/warn.exr", 4, 2, 3, 0.5f, {{0, 0, 0.52f}});
  // Pixel 1 a little over --fail, pixel 2 the most, pixel 3 not over it, pixel 4 infinite.
  image("A/sub/fail.exr", 4, 2, 3, 0.5f);
  image("B/sub/fail.exr", 4, 2, 3, 0.5f,
        {{1, 0, 0.65f}, {2, 2, 1.5f}, {3, 1, 0.55f}, {4, 0, std::numeric_limits<float>::infinity()}});
  DiffOptions o = thresholds(0.1, 0.01);
  o.heat_map_dir = path("out1");
  const DiffReport r = diff_images(path("A"), path("B"), o);
  ASSERT_EQ(r.pairs.size(), 3u);
  EXPECT_EQ(r.pairs[0].heat_map, "");
  EXPECT_EQ(r.pairs[1].status, DiffStatus::kFail);
  EXPECT_EQ(r.pairs[1].heat_map, path("out1/sub/fail.exr.diff.png"));
  EXPECT_EQ(r.pairs[2].status, DiffStatus::kWarn);
  EXPECT_EQ(r.pairs[2].heat_map, "");
  size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir_ / "out1")) files += e.is_regular_file();
  EXPECT_EQ(files, 1u);  // no temporaries left, nothing for passing or warning pairs

  auto in = OIIO::ImageInput::open(r.pairs[1].heat_map);
  ASSERT_TRUE(in) << OIIO::geterror();
  ASSERT_EQ(in->spec().width, 4);
  ASSERT_EQ(in->spec().height, 2);
  ASSERT_EQ(in->spec().nchannels, 3);
  std::vector<uint8_t> rgb(4 * 2 * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, rgb.data()));
  auto px = [&rgb](size_t i) { return std::vector<int>{rgb[i * 3], rgb[i * 3 + 1], rgb[i * 3 + 2]}; };
  EXPECT_EQ(px(0), (std::vector<int>{0, 0, 0}));        // equal
  EXPECT_EQ(px(3), (std::vector<int>{0, 0, 0}));        // 0.05: not over --fail 0.1
  EXPECT_EQ(px(2), (std::vector<int>{253, 231, 37}));   // the max: viridis's top (yellow)
  EXPECT_EQ(px(4), (std::vector<int>{255, 255, 255}));  // infinite
  EXPECT_LT(px(1)[1], 100);                             // 0.15, near the bottom: dark
  EXPECT_GT(px(1)[2], 50);                              // viridis's dark end is purple

  o.heat_map_dir = path("out2");
  const DiffReport again = diff_images(path("A"), path("B"), o);
  EXPECT_EQ(read_file(again.pairs[1].heat_map), read_file(r.pairs[1].heat_map));
}

TEST_F(ImageDiffTest, HeatMapThatCannotBeWrittenIsAnOutputError) {
  const std::string a = image("a.png", 2, 2, 3, 0.0f), b = image("b.png", 2, 2, 3, 1.0f);
  text_file("blocker", "");
  DiffOptions o;
  o.heat_map_dir = path("blocker/out");  // a file where a folder should be
  EXPECT_THROW(diff_images(a, b, o), OutputError);
}

// A report with one pair of each kind, for the report formats.
class ImageDiffReportTest : public ImageDiffTest {
protected:
  DiffReport report() {
    image("A/a&b <\"q\">.png", 4, 4, 3, 0.5f);
    image("B/a&b <\"q\">.png", 4, 4, 3, 0.5f);
    image("A/fail.png", 4, 4, 3, 0.0f);
    image("B/fail.png", 4, 4, 3, 0.0f, {{0, 0, 1.0f}});
    image("A/gone.png", 2, 2, 3, 0.0f);
    image("A/warn.exr", 4, 4, 3, 0.0f);
    image("B/warn.exr", 4, 4, 3, 0.0f, {{1, 2, 0.05f}});
    return diff_images(path("A"), path("B"), thresholds(0.1, 0.01));
  }
};

TEST_F(ImageDiffReportTest, TextHasOneLinePerPairAndASummary) {
  const std::string text = diff_text(report());
  const std::string expected =
      "PASS  a&b <\"q\">.png  max 0  mean 0  RMS 0  PSNR inf dB  over warn 0 (0%)  over fail 0 (0%)\n"
      "FAIL  fail.png  max 1 at (0, 0, R)  mean 0.0208333  RMS 0.144338  PSNR 16.8124 dB  over warn 1 (6.25%)  "
      "over fail 1 (6.25%)\n"
      "FAIL  gone.png  missing in B, only in A\n"
      "WARN  warn.exr  max 0.05 at (1, 0, B)  mean 0.00104167  RMS 0.00721688  PSNR 42.833 dB  over warn 1 (6.25%)  "
      "over fail 0 (0%)\n"
      "summary: FAIL (4 pairs: 1 pass, 1 warn, 2 fail)\n";
  EXPECT_EQ(text, expected);
}

TEST_F(ImageDiffReportTest, JsonIsOneDocumentWithMetricsAndNullForInfinity) {
  const json doc = json::parse(diff_json(report()));
  EXPECT_EQ(doc["a"], path("A"));
  EXPECT_EQ(doc["thresholds"]["fail"], 0.1);
  EXPECT_TRUE(doc["thresholds"]["hard_fail"].is_null());
  ASSERT_EQ(doc["pairs"].size(), 4u);
  const json& pass = doc["pairs"][0];
  EXPECT_EQ(pass["status"], "PASS");
  EXPECT_TRUE(pass["psnr"].is_null());
  EXPECT_TRUE(pass["reason"].is_null());
  EXPECT_EQ(pass["max_error"], 0.0);
  const json& fail = doc["pairs"][1];
  EXPECT_EQ(fail["name"], "fail.png");
  EXPECT_EQ(fail["status"], "FAIL");
  EXPECT_EQ(fail["max_error"], 1.0);
  EXPECT_EQ(fail["max_at"], json({{"x", 0}, {"y", 0}, {"channel", "R"}}));
  EXPECT_EQ(fail["pixels"], 16);
  EXPECT_EQ(fail["pixels_over_fail"], 1);
  EXPECT_EQ(fail["reason"], "1 pixel (6.25%) over --fail 0.1, more than --failpercent 0");
  const json& gone = doc["pairs"][2];
  EXPECT_TRUE(gone["b"].is_null());
  EXPECT_EQ(gone["problem"], "missing in B, only in A");
  EXPECT_FALSE(gone.contains("max_error"));
  EXPECT_EQ(doc["summary"], json({{"status", "FAIL"}, {"pairs", 4}, {"pass", 1}, {"warn", 1}, {"fail", 2}}));
}

TEST_F(ImageDiffReportTest, JunitHasATestcasePerPairAndEscapesNames) {
  const DiffReport r = report();
  const std::string x = diff_junit(r);
  EXPECT_EQ(x.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"dqskin diff\" tests=\"4\" failures=\"2\"", 0), 0u) << x;
  EXPECT_NE(x.find("<testcase classname=\"dqskin.diff\" name=\"a&amp;b &lt;&quot;q&quot;&gt;.png\"/>"), std::string::npos) << x;
  EXPECT_NE(x.find("<failure type=\"FAIL\" message=\"1 pixel (6.25%) over --fail 0.1, more than --failpercent 0\">A: "),
            std::string::npos) << x;
  EXPECT_NE(x.find("max error: 1 at (0, 0, R)\n"), std::string::npos) << x;
  EXPECT_NE(x.find("<failure type=\"FAIL\" message=\"missing in B, only in A\">"), std::string::npos) << x;
  EXPECT_NE(x.find("<system-out>WARN: 1 pixel (6.25%) over --warn 0.01"), std::string::npos) << x;
  EXPECT_NE(x.find("<property name=\"hardfail\" value=\"inf\"/>"), std::string::npos) << x;
  EXPECT_EQ(x.find("time"), std::string::npos);  // nothing that changes from run to run
  EXPECT_EQ(diff_junit(r), x);
}

TEST(ImageDiffJunit, ReplacesInvalidUtf8AndControlCharacters) {
  DiffReport r;
  r.a = "A";
  r.b = "B";
  ImageDiff d;
  d.name = std::string("caf\xC3\xA9-\xFF-\x01-\xE2\x82-line\nbreak.png");
  d.status = DiffStatus::kFail;
  d.problem = d.reason = "missing in B, only in A";
  r.pairs.push_back(d);
  const std::string x = diff_junit(r);
  EXPECT_NE(x.find("name=\"caf\xC3\xA9-\xEF\xBF\xBD-\xEF\xBF\xBD-\xEF\xBF\xBD\xEF\xBF\xBD-line&#10;break.png\""),
            std::string::npos) << x;
}

}  // namespace
}  // namespace dqskin
