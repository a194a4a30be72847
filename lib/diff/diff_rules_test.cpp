// Masks and preset rules of `dqskin diff`: which pixels are left out and how the figures count the rest;
// which rule a pair follows; and the preset file's one-line errors.
#include "dqskin/error.hpp"
#include "dqskin/image_diff.hpp"
#include "../test_support/image_diff_fixture_oiio.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace dqskin {
namespace {

TEST(DiffGlob, StarsQuestionMarksAndFolders) {
  EXPECT_TRUE(glob_match("*.png", "a.png"));
  EXPECT_FALSE(glob_match("*.png", "sub/a.png"));  // one star stays in its folder
  EXPECT_TRUE(glob_match("**/*.png", "sub/deeper/a.png"));
  EXPECT_TRUE(glob_match("**", "anything/at/all.exr"));
  EXPECT_TRUE(glob_match("ui/frame_00?.png", "ui/frame_007.png"));
  EXPECT_FALSE(glob_match("ui/frame_00?.png", "ui/frame_0007.png"));
  EXPECT_FALSE(glob_match("?", "/"));
  EXPECT_TRUE(glob_match("characters/**/hero_*.png", "characters/a/b/hero_run.png"));
  EXPECT_FALSE(glob_match("characters/**/hero_*.png", "characters/a/b/villain.png"));
  EXPECT_TRUE(glob_match("a*b*c", "aXbYbZc"));
  EXPECT_TRUE(glob_match("**/a.png", "a.png"));  // "**/" may stand for no folder
  // Many stars against a long name that does not match: |pattern| × |name| steps, not a search.
  EXPECT_FALSE(glob_match("*a*a*a*a*a*a*a*a*a*a*a*a*a*a*a*a*a*a*a*a*b", std::string(200, 'a')));
  EXPECT_TRUE(glob_match(std::string(50, '*') + "b", std::string(300, 'a') + "b"));
  EXPECT_FALSE(glob_match("a", "ab"));
}

class DiffRulesTest : public ImageDiffTest {
protected:
  std::string preset(const std::string& text) { return text_file("preset.json", text); }
  std::string error_of(const std::string& text) {
    try {
      read_diff_rules(preset(text));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(DiffRulesTest, PresetRulesAreReadInOrder) {
  const std::vector<DiffRule> rules = read_diff_rules(preset(R"({"rules": [
    {"match": "ui/*", "fail": 0.02, "failpercent": 1},
    {"match": "**", "metric": "flip", "failmean": 0.05, "ppd": 40, "mask": "masks/hud.png", "ignore": [[0, 0, 10, 5]]}]})"));
  ASSERT_EQ(rules.size(), 2u);
  EXPECT_EQ(rules[0].metric, DiffMetric::kIdiff);
  EXPECT_EQ(rules[0].thresholds.fail, 0.02);
  EXPECT_EQ(rules[0].thresholds.fail_percent, 1.0);
  EXPECT_EQ(rules[0].thresholds.warn, 1e-6);  // idiff's default where the rule gives none
  EXPECT_EQ(rules[1].metric, DiffMetric::kFlip);
  EXPECT_EQ(rules[1].thresholds.fail_mean, 0.05);
  EXPECT_TRUE(std::isinf(rules[1].thresholds.fail));  // FLIP: only the rules given
  EXPECT_EQ(rules[1].pixels_per_degree, 40.0);
  EXPECT_EQ(rules[1].mask.images, std::vector<std::string>{path("masks/hud.png")});  // beside the preset file
  ASSERT_EQ(rules[1].mask.rects.size(), 1u);
  EXPECT_EQ(rules[1].mask.rects[0].width, 10);

  DiffOptions o;
  o.rules = rules;
  o.mask.images = {path("cli_mask.png")};
  EXPECT_EQ(options_for(o, "scene/hero.png").mask.images,
            (std::vector<std::string>{path("cli_mask.png"), path("masks/hud.png")}));  // added, not replaced
  EXPECT_EQ(options_for(o, "ui/button.png").thresholds.fail, 0.02);
  EXPECT_EQ(options_for(o, "ui/button.png").metric, DiffMetric::kIdiff);
  EXPECT_EQ(options_for(o, "scene/hero.png").metric, DiffMetric::kFlip);
  EXPECT_EQ(options_for(o, "scene/hero.png").pixels_per_degree, 40.0);
}

TEST_F(DiffRulesTest, BadPresetsSayWhatIsWrong) {
  const std::string p = path("preset.json");
  EXPECT_EQ(error_of("{\"rules\": [").rfind(p + ": not JSON: ", 0), 0u);  // then the parser's own words
  EXPECT_EQ(error_of("[]"), p + ": a preset file is an object with an array \"rules\"");
  EXPECT_EQ(error_of(R"({"rules": [], "extra": 1})"), p + ": unknown key \"extra\" (a preset has \"rules\")");
  EXPECT_EQ(error_of(R"({"rules": [{"fail": 0.1}]})"), p + ": rules[0]: \"match\" (a name pattern) is required");
  EXPECT_EQ(error_of(R"({"rules": [{"match": "*", "fial": 0.1}]})"), p + ": rules[0]: unknown key \"fial\"");
  EXPECT_EQ(error_of(R"({"rules": [{"match": "*", "fail": "0.1"}]})"), p + ": rules[0]: \"fail\" must be a number");
  EXPECT_EQ(error_of(R"({"rules": [{"match": "*", "failpercent": 101}]})"),
            p + ": rules[0]: \"failpercent\" must be from 0 to 100, not 101");
  EXPECT_EQ(error_of(R"({"rules": [{"match": "*", "metric": "yee"}]})"), p + ": rules[0]: \"metric\" must be \"idiff\" or \"flip\"");
  EXPECT_EQ(error_of(R"({"rules": [{"match": "*", "ppd": 40}]})"),
            p + ": rules[0]: \"ppd\" is FLIP's: give it with \"metric\": \"flip\"");
  EXPECT_EQ(error_of(R"({"rules": [{"match": "*", "metric": "flip", "failpercent": 1}]})"),
            p + ": rules[0]: \"failpercent\" needs \"fail\" with the flip metric");
  EXPECT_EQ(error_of(R"({"rules": [{"match": "*", "ignore": [[0, 0, 0, 4]]}]})"),
            p + ": rules[0]: \"ignore\" must be from 1 to 1.67772e+07, not 0");
  EXPECT_EQ(error_of(R"({"rules": [{"match": "*", "ignore": [1, 2]}]})"),
            p + ": rules[0]: each \"ignore\" rectangle is [x, y, width, height]");
  try {
    read_diff_rules(path("none.json"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path("none.json") + ": cannot read the preset file");
  }
}

TEST_F(DiffRulesTest, RectanglesLeaveOutPixelsAndTheFiguresCountTheRest) {
  // 4 × 4, one pixel at (3, 3) off by 0.4 and one at (0, 0) off by 0.2; the rectangle covers (0, 0).
  const std::string a = image("a.png", 4, 4, 3, 0.2f);
  const std::string b = image("b.png", 4, 4, 3, 0.2f, {{15, 0, 0.6f}, {0, 1, 0.4f}});
  DiffOptions o;
  o.thresholds.fail = 0.1;
  const ImageDiff whole = diff_pair({"p", a, b, ""}, o);
  o.mask.rects.push_back({0, 0, 2, 1});
  const ImageDiff masked = diff_pair({"p", a, b, ""}, o);
  EXPECT_EQ(whole.over_fail, 2u);
  EXPECT_EQ(masked.over_fail, 1u);
  EXPECT_EQ(masked.masked, 2u);
  EXPECT_EQ(masked.pixels, 14u);
  // The mean over the 14 pixels compared (3 channels each): one channel off by 0.4 (8-bit rounded).
  const double step = (std::round(0.6 * 255) - std::round(0.2 * 255)) / 255;
  EXPECT_NEAR(masked.mean_error, step / (14 * 3), 1e-7);
  EXPECT_NEAR(masked.rms_error, std::sqrt(step * step / (14 * 3)), 1e-7);
  EXPECT_NEAR(masked.psnr, 20 * std::log10(1 / masked.rms_error), 1e-9);
  o.mask.rects.push_back({3, 3, 100, 100});  // beyond the image: clipped
  const ImageDiff none_left = diff_pair({"p", a, b, ""}, o);
  EXPECT_EQ(none_left.status, DiffStatus::kPass);
  EXPECT_EQ(none_left.max_error, 0.0);
}

TEST_F(DiffRulesTest, AMaskImageLeavesOutItsWhitePixelsAlsoForFlip) {
  // A difference under the mask: nothing counts, and nothing spreads through FLIP's filters around it.
  const std::string a = image("a.png", 32, 32, 3, 0.0f);
  const std::string b = image("b.png", 32, 32, 3, 0.0f, {{16 * 32 + 16, 0, 1.0f}, {16 * 32 + 16, 1, 1.0f}});
  const std::string mask = image("mask.png", 32, 32, 1, 0.0f, {{16 * 32 + 16, 0, 1.0f}});
  DiffOptions o;
  o.metric = DiffMetric::kFlip;
  o.thresholds = flip_thresholds({}, {});
  EXPECT_EQ(diff_pair({"p", a, b, ""}, o).status, DiffStatus::kFail);
  o.mask.images = {mask};
  const ImageDiff d = diff_pair({"p", a, b, ""}, o);
  EXPECT_EQ(d.status, DiffStatus::kPass) << d.reason;
  EXPECT_EQ(d.max_error, 0.0);
  EXPECT_EQ(d.masked, 1u);
  EXPECT_EQ(d.pixels, 32u * 32u - 1u);
}

TEST_F(DiffRulesTest, AMaskOfAnotherSizeIsAnInputError) {
  const std::string a = image("a.png", 8, 8, 3, 0.0f), b = image("b.png", 8, 8, 3, 0.1f);
  DiffOptions o;
  o.mask.images = {image("mask.png", 4, 8, 1, 1.0f)};
  try {
    diff_pair({"p", a, b, ""}, o);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), o.mask.images[0] + ": the mask is 4x8, the images 8x8");
  }
  o.mask.images = {path("missing.png")};
  EXPECT_THROW(diff_pair({"p", a, b, ""}, o), InputError);
}

TEST_F(DiffRulesTest, FoldersFollowTheFirstMatchingRule) {
  image("A/ui/b.png", 4, 4, 3, 0.5f);
  image("B/ui/b.png", 4, 4, 3, 0.51f);
  image("A/scene.png", 4, 4, 3, 0.5f);
  image("B/scene.png", 4, 4, 3, 0.51f);
  DiffOptions o;  // idiff's defaults: both would fail
  o.rules = read_diff_rules(preset(R"({"rules": [{"match": "ui/*", "fail": 0.1, "warn": 0.05}]})"));
  const DiffReport r = diff_images(path("A"), path("B"), o);
  ASSERT_EQ(r.pairs.size(), 2u);
  EXPECT_EQ(r.pairs[0].name, "scene.png");
  EXPECT_EQ(r.pairs[0].status, DiffStatus::kFail);
  EXPECT_EQ(r.pairs[0].rule, "");
  EXPECT_EQ(r.pairs[1].status, DiffStatus::kPass);
  EXPECT_EQ(r.pairs[1].rule, "ui/*");
  EXPECT_EQ(r.pairs[1].thresholds.fail, 0.1);
}

}  // namespace
}  // namespace dqskin
