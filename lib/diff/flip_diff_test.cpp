// `dqskin diff --metric flip` through the library: files read as diff reads them (8-bit display values,
// float linear light, grey and alpha), the verdict of the FLIP thresholds, the reports, the heat map and
// the memory ceiling. The FLIP values themselves are flip_test.cpp's; here they must come through unchanged.
#include "dqskin/diff_report.hpp"
#include "dqskin/image_diff.hpp"
#include "../test_support/read_file.hpp"
#include "flip.hpp"
#include "flip_heat_map.hpp"
#include "../test_support/image_diff_fixture_oiio.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>

namespace dqskin {
namespace {

using nlohmann::json;
using testing_support::read_file;

DiffOptions flip_options(const std::vector<std::string>& given = {}, const DiffThresholds& values = {}) {
  DiffOptions o;
  o.metric = DiffMetric::kFlip;
  o.thresholds = flip_thresholds(values, given);
  return o;
}

// One white pixel in a black 64 × 64 image (flip_test.cpp's OneChangedPixel).
class FlipDiffTest : public ImageDiffTest {
protected:
  void SetUp() override {
    black_ = image("black.png", 64, 64, 3, 0.0f);
    dot_ = image("dot.png", 64, 64, 3, 0.0f, {{32 * 64 + 32, 0, 1.0f}, {32 * 64 + 32, 1, 1.0f}, {32 * 64 + 32, 2, 1.0f}});
  }
  std::string black_, dot_;
};

TEST_F(FlipDiffTest, IdenticalImagesPassWithZero) {
  const ImageDiff d = diff_pair({"same", black_, black_, "same.diff.png"}, flip_options());
  EXPECT_EQ(d.status, DiffStatus::kPass) << d.reason;
  EXPECT_EQ(d.metric, DiffMetric::kFlip);
  EXPECT_EQ(d.max_error, 0.0);
  EXPECT_EQ(d.mean_error, 0.0);
  EXPECT_TRUE(std::isnan(d.psnr));
}

TEST_F(FlipDiffTest, OneChangedPixelHasTheCoresFiguresAndFailsByDefault) {
  const ImageDiff d = diff_pair({"dot", black_, dot_, "dot.diff.png"}, flip_options());
  ASSERT_TRUE(d.compared) << d.problem;
  EXPECT_NEAR(d.max_error, 0.864906, 1e-6);
  EXPECT_NEAR(d.mean_error, 0.0034940, 1e-6);
  EXPECT_EQ(d.max_x, 32);
  EXPECT_EQ(d.max_y, 32);
  EXPECT_EQ(d.max_channel, "");
  EXPECT_EQ(d.pixels, 64u * 64u);
  EXPECT_LE(d.flip_q1, d.flip_median);
  EXPECT_LE(d.flip_median, d.flip_q3);
  EXPECT_LE(d.flip_q3, d.max_error);
  EXPECT_EQ(d.status, DiffStatus::kFail);  // no threshold given: any visible difference
  EXPECT_EQ(d.reason, "mean error 0.00349404 over --failmean 0");
}

TEST_F(FlipDiffTest, OnlyTheGivenThresholdsJudge) {
  DiffThresholds v;
  v.fail_mean = 0.01;
  EXPECT_EQ(diff_pair({"dot", black_, dot_, ""}, flip_options({"--failmean"}, v)).status, DiffStatus::kPass);
  v.hard_fail = 0.8;
  const ImageDiff hard = diff_pair({"dot", black_, dot_, ""}, flip_options({"--failmean", "--hardfail"}, v));
  EXPECT_EQ(hard.status, DiffStatus::kFail);
  EXPECT_EQ(hard.reason, "max error 0.864906 over --hardfail 0.8");
  v.warn_mean = 0.001;
  EXPECT_EQ(diff_pair({"dot", black_, dot_, ""}, flip_options({"--failmean", "--warnmean"}, v)).status, DiffStatus::kWarn);

  // The percentile rule: pixels over --fail counted on the FLIP map, as many as the core's map has.
  const std::vector<float> black(64 * 64 * 3, 0.0f);
  std::vector<float> dot = black;
  std::fill_n(dot.begin() + 3 * (32 * 64 + 32), 3, 1.0f);
  const std::vector<double> map = flip_error_map(black.data(), dot.data(), 64, 64);
  const auto over = uint64_t(std::count_if(map.begin(), map.end(), [](double e) { return e > 0.3; }));
  ASSERT_GT(over, 1u);
  v.fail = 0.3;
  v.fail_percent = 100.0 * double(over) / 4096.0 - 0.01;  // one pixel less than those over it: fails
  const ImageDiff percentile = diff_pair({"dot", black_, dot_, ""}, flip_options({"--fail", "--failpercent"}, v));
  EXPECT_EQ(percentile.over_fail, over);
  EXPECT_EQ(percentile.status, DiffStatus::kFail);
  v.fail_percent += 0.02;
  EXPECT_EQ(diff_pair({"dot", black_, dot_, ""}, flip_options({"--fail", "--failpercent"}, v)).status, DiffStatus::kPass);
}

TEST(FlipThresholds, NoneGivenFailsAnyDifferenceOthersAreOff) {
  const DiffThresholds none = flip_thresholds({}, {});
  EXPECT_EQ(none.fail_mean, 0.0);
  EXPECT_TRUE(std::isinf(none.fail) && std::isinf(none.warn) && std::isinf(none.hard_fail) && std::isinf(none.warn_mean));
  DiffThresholds values;
  values.warn_mean = 0.02;
  const DiffThresholds warn_only = flip_thresholds(values, {"--warnmean"});
  EXPECT_EQ(warn_only.warn_mean, 0.02);
  EXPECT_TRUE(std::isinf(warn_only.fail_mean));  // idiff's fail 1e-6 is not kept either
  EXPECT_TRUE(std::isinf(warn_only.fail));
}

TEST_F(ImageDiffTest, FlipReadsGreyAsRgbAndSeesAlphaOverBlack) {
  // OpenImageIO reads colours multiplied by their alpha: what a viewer shows over black. Pixel 7 is
  // transparent in both, whatever its colour; in the third image it is opaque.
  const std::string rgba = image("rgba.png", 16, 16, 4, 0.5f, {{7, 3, 0.0f}});
  const std::string grey_alpha = image("ga.png", 16, 16, 2, 0.5f, {{7, 1, 0.0f}});
  const DiffOptions o = flip_options();
  EXPECT_EQ(diff_pair({"rgba", rgba, image("rgba2.png", 16, 16, 4, 0.5f, {{7, 3, 0.0f}, {7, 0, 0.2f}}), ""}, o).max_error, 0.0);
  EXPECT_GT(diff_pair({"rgba", rgba, image("rgba3.png", 16, 16, 4, 0.5f), ""}, o).max_error, 0.1);
  // One channel, or grey and alpha, is grey: the same as the RGB image of that grey.
  const std::string grey = image("grey.png", 16, 16, 1, 0.5f), rgb = image("rgb5.png", 16, 16, 3, 0.5f);
  const std::string darker1 = image("d1.png", 16, 16, 1, 0.4f), darker3 = image("d3.png", 16, 16, 3, 0.4f);
  EXPECT_EQ(diff_pair({"1", grey, darker1, ""}, o).mean_error, diff_pair({"3", rgb, darker3, ""}, o).mean_error);
  const std::string black_at_7 = image("g.png", 16, 16, 1, 0.5f, {{7, 0, 0.0f}});
  const std::string grey_alpha_b = image("ga2.png", 16, 16, 2, 0.5f);
  EXPECT_EQ(diff_pair({"ga", grey_alpha, grey_alpha_b, ""}, o).mean_error,
            diff_pair({"g", black_at_7, grey, ""}, o).mean_error);
}

TEST_F(ImageDiffTest, FlipMeasuresFloatFilesWithHdrFlip) {
  // Linear light: HDR-FLIP, as flip_test.cpp's HdrFlip cases; a uniform 3.0 against 3.75 is one of them.
  const std::string a = image("a.exr", 24, 24, 3, 3.0f), b = image("b.exr", 24, 24, 3, 3.75f);
  const ImageDiff d = diff_pair({"exr", a, b, ""}, flip_options());
  ASSERT_TRUE(d.compared) << d.problem;
  EXPECT_EQ(d.hdr_exposures, 2);
  const std::vector<float> ra(24 * 24 * 3, 3.0f), rb(24 * 24 * 3, 3.75f);
  const std::vector<double> map = hdr_flip_error_map(ra.data(), rb.data(), 24, 24);
  EXPECT_NEAR(d.mean_error, map[0], 1e-12);  // summed over the pixels
  EXPECT_DOUBLE_EQ(d.max_error, map[0]);
  EXPECT_NE(diff_text(diff_images(a, b, flip_options())).find("HDR-FLIP mean "), std::string::npos);
}

TEST_F(ImageDiffTest, FlipRefusesDisplayValuesAgainstLinearLight) {
  const std::string png = image("a.png", 8, 8, 3, 0.5f), exr = image("b.exr", 8, 8, 3, 0.5f);
  const ImageDiff d = diff_pair({"mixed", png, exr, ""}, flip_options());
  EXPECT_FALSE(d.compared);
  EXPECT_EQ(d.status, DiffStatus::kFail);
  EXPECT_EQ(d.problem, "FLIP compares like with like: A holds display values (integer), B linear light (float)");
}

TEST_F(FlipDiffTest, HeatMapIsMagmaWithALegendAndTheSameBytesTwice) {
  DiffOptions o = flip_options();
  o.heat_map_dir = path("out1");
  const ImageDiff d = diff_pair({"dot", black_, dot_, "dot.png.diff.png"}, o);
  ASSERT_EQ(d.heat_map, path("out1/dot.png.diff.png"));
  auto in = OIIO::ImageInput::open(d.heat_map);
  ASSERT_TRUE(in) << OIIO::geterror();
  const diff_detail::FlipHeatMapSize size = diff_detail::flip_heat_map_size(64, 64);
  ASSERT_EQ(in->spec().width, size.width);
  ASSERT_EQ(in->spec().height, size.height);
  ASSERT_GT(size.width, 64 + 20);   // the legend's panel
  ASSERT_GE(size.height, 64);       // tall enough for the legend
  ASSERT_EQ(in->spec().nchannels, 3);
  std::vector<uint8_t> rgb(size_t(size.width) * size_t(size.height) * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, rgb.data()));
  auto px = [&](int x, int y) {
    const size_t i = (size_t(y) * size_t(size.width) + size_t(x)) * 3;
    return std::vector<int>{rgb[i], rgb[i + 1], rgb[i + 2]};
  };
  for (int c : px(0, 0)) EXPECT_LT(c, 8);  // FLIP 0: magma's black
  const std::vector<int> worst = px(32, 32);  // 0.86: magma's orange-yellow end, red strongest
  EXPECT_GT(worst[0], 230);
  EXPECT_GT(worst[0], worst[1]);
  EXPECT_GT(worst[1], worst[2]);
  o.heat_map_dir = path("out2");
  EXPECT_EQ(read_file(diff_pair({"dot", black_, dot_, "dot.png.diff.png"}, o).heat_map), read_file(d.heat_map));
}

TEST_F(FlipDiffTest, MemoryCeilingCountsFlipsWork) {
  DiffOptions o = flip_options();
  o.max_memory = 200 * 1024;  // the two images (48 KiB each as float) fit; FLIP's bands do not
  const ImageDiff d = diff_pair({"dot", black_, dot_, ""}, o);
  EXPECT_FALSE(d.compared);
  EXPECT_EQ(d.unreadable, dot_);
  EXPECT_NE(d.read_error.find(" and FLIP), more than --max-memory 200 KiB"), std::string::npos) << d.read_error;
}

TEST_F(FlipDiffTest, ReportsNameTheMetricAndFlipsFigures) {
  DiffOptions o = flip_options();
  o.pixels_per_degree = 40;
  const DiffReport r = diff_images(black_, dot_, o);
  const std::string text = diff_text(r);
  EXPECT_NE(text.find("FAIL  " + black_ + "  FLIP mean "), std::string::npos) << text;
  EXPECT_NE(text.find("  weighted quartiles "), std::string::npos) << text;
  EXPECT_NE(text.find(" at (32, 32)  over warn 0 (0%)  over fail 0 (0%)\n"), std::string::npos) << text;
  const json doc = json::parse(diff_json(r));
  EXPECT_EQ(doc["metric"], "flip");
  EXPECT_EQ(doc["pixels_per_degree"], 40.0);
  EXPECT_EQ(doc["thresholds"]["fail_mean"], 0.0);
  EXPECT_TRUE(doc["thresholds"]["fail"].is_null());
  const json& p = doc["pairs"][0];
  EXPECT_EQ(p["weighted_quartiles"].size(), 3u);
  EXPECT_TRUE(p["psnr"].is_null());
  EXPECT_FALSE(p["max_at"].contains("channel"));
  const std::string junit = diff_junit(r);
  EXPECT_NE(junit.find("<property name=\"metric\" value=\"flip\"/>"), std::string::npos);
  EXPECT_NE(junit.find("<property name=\"pixels_per_degree\" value=\"40\"/>"), std::string::npos);
  EXPECT_NE(junit.find("FLIP mean: "), std::string::npos);
}

TEST_F(ImageDiffTest, FlipAtAnotherViewingDistanceGivesAnotherValue) {
  const std::string a = image("a.png", 32, 32, 3, 0.0f, {{16 * 32 + 16, 1, 1.0f}});
  const std::string b = image("b.png", 32, 32, 3, 0.0f);
  DiffOptions near = flip_options(), far = flip_options();
  near.pixels_per_degree = 20;  // close to the screen: a pixel spans more of the eye, the filters are narrower
  EXPECT_GT(diff_pair({"x", a, b, ""}, near).max_error, diff_pair({"x", a, b, ""}, far).max_error);
}

}  // namespace
}  // namespace dqskin
