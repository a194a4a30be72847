// The HTML page of `dqskin report` from report.json documents built here: a small fixture (two joints, two
// clips, nulls where the format allows them, a joint name with markup characters, one PNG written by
// lib/render's image writer) and a BrainStem-sized one (20 joints, 1,047 frames). With
// DQSKIN_REPORT_PAGE_DIR set, ReportPageFixture writes pages for the browser check (report_check.mjs).
#include "report_html.hpp"
#include "report_numbers.hpp"
#include "../test_support/base64.hpp"
#include "../test_support/read_file.hpp"
#include "../test_support/scratch_dir.hpp"

#include "dqskin/image_output.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace dqskin::report_detail {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

const std::string kOddName = "Arm<&\">'";

// A small heat-coloured PNG, written by lib/render's PNG writer.
std::vector<uint8_t> test_png(const fs::path& folder) {
  Image image;
  image.width = 48, image.height = 24;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float t = float(x) / float(image.width - 1);
      image.rgba.insert(image.rgba.end(), {t, 0.6f * (1 - t) + 0.2f, float(y) / float(image.height), 1.0f});
    }
  const fs::path path = folder / "test.png";
  write_image(path.string(), image, ImageFormat::kPng);
  const std::string bytes = testing_support::read_file(path);
  return {bytes.begin(), bytes.end()};
}

json series(size_t frames, double base, double amplitude, double phase) {
  json values = json::array();
  for (size_t i = 0; i < frames; ++i) values.push_back(base + amplitude * std::sin(0.7 * double(i) + phase));
  return values;
}
json nulls(size_t frames) {
  json values = json::array();
  for (size_t i = 0; i < frames; ++i) values.push_back(nullptr);
  return values;
}
json times(size_t frames, double fps) {
  json values = json::array();
  for (size_t i = 0; i < frames; ++i) values.push_back(double(i) / fps);
  return values;
}

json joint_clip(const std::string& clip, size_t frames, bool root, double scale) {
  json s = {{"lbs_dib_max", series(frames, 0.006 * scale, 0.005 * scale, 0)},
            {"lbs_dib_mean", series(frames, 0.002 * scale, 0.001 * scale, 0)},
            {"dqs_dib_max", series(frames, 0.0006 * scale, 0.0004 * scale, 1)},
            {"dqs_dib_mean", series(frames, 0.0002 * scale, 0.0001 * scale, 1)},
            {"lbs_dqs_max", series(frames, 0.006 * scale, 0.005 * scale, 0.2)},
            {"area_lbs", root ? nulls(frames) : series(frames, 0.6, 0.35, 0)},
            {"area_dqs", root ? nulls(frames) : series(frames, 1.02, 0.02, 0.5)},
            {"area_dib", root ? nulls(frames) : series(frames, 1.0, 0.005, 0.5)},
            {"twist", root ? nulls(frames) : series(frames, 60, 100, 0)},
            {"bend", root ? nulls(frames) : series(frames, 10, 25, 2)},
            {"flips", series(frames, 0, 0, 0)}};
  if (!root) s["lbs_dib_max"][2] = nullptr;  // a gap in the middle of a line
  return {{"clip", clip}, {"series", s}};
}

// Two joints (a flagged child with an awkward name, a fine root without cross-section or parent), two
// clips (Walk with a volume and a contact sheet, "Run <fast>" with neither).
json fixture_report() {
  json report;
  report["dqskin_report"] = 1;
  report["tool"] = "dqskin 0.9.0";
  report["input"] = {{"file", "rig <test>.glb"}, {"sha256", std::string(64, 'a')}, {"vertices", 1728},
                     {"skinned_vertices", 1700}, {"skins", 1}};
  report["diagonal"] = 1.2345;
  report["settings"] = {{"fps", 10}, {"tolerance", 0.005}, {"candy_wrapper_fail", 0.5}};
  report["verdict"] = {{"code", "use-dqs"}, {"text", "use dqs: lbs collapses the cross-section of " + kOddName},
                       {"joints", {kOddName}}};
  json walk = {{"name", "Walk"}, {"frames", 8}, {"fps", 10}, {"times", times(8, 10)},
               {"volume", {{"rest", 0.0123}, {"lbs", series(8, 0.97, 0.02, 0)}, {"dqs", series(8, 1.01, 0.005, 0)},
                           {"dib", series(8, 1.0, 0.002, 0)}}},
               {"worst_frame", 3}, {"image", "worst_Walk.png"}};
  json run = {{"name", "Run <fast>"}, {"frames", 5}, {"fps", 10}, {"times", times(5, 10)},
              {"volume", nullptr}, {"worst_frame", 1}, {"image", nullptr}};
  report["clips"] = {walk, run};
  json arm = {{"skin", 0}, {"joint", 1}, {"node", 2}, {"name", kOddName}, {"parent", "Root"}, {"vertices", 143},
              {"summary", {{"lbs_dib_max", 0.0123456789}, {"dqs_dib_max", 0.00091}, {"lbs_dqs_max", 0.0121},
                           {"candy_wrapper", 0.93}, {"dqs_bulge", 0.04}, {"area_lbs_min", 0.07}, {"area_dqs_min", 0.99},
                           {"twist_max", 170.2}, {"bend_max", 35}, {"flips", 12},
                           {"worst", {{"clip", "Walk"}, {"frame", 3}}}}},
              {"verdict", {{"code", "add-twist-joints"}, {"text", "add twist joints: " + kOddName + " twists 170° in Walk"}}},
              {"clips", {joint_clip("Walk", 8, false, 1), joint_clip("Run <fast>", 5, false, 0.5)}}};
  json root = {{"skin", 0}, {"joint", 0}, {"node", 1}, {"name", "Root"}, {"parent", nullptr}, {"vertices", 1557},
               {"summary", {{"lbs_dib_max", 2.5e-7}, {"dqs_dib_max", 0.0}, {"lbs_dqs_max", 2.5e-7},
                            {"candy_wrapper", nullptr}, {"dqs_bulge", nullptr}, {"area_lbs_min", nullptr},
                            {"area_dqs_min", nullptr}, {"twist_max", nullptr}, {"bend_max", nullptr}, {"flips", 0},
                            {"worst", {{"clip", "Run <fast>"}, {"frame", 1}}}}},
               {"verdict", {{"code", "lbs-fine"}, {"text", "lbs is fine"}}},
               {"clips", {joint_clip("Walk", 8, true, 0.01), joint_clip("Run <fast>", 5, true, 0.01)}}};
  report["joints"] = {arm, root};
  report["images"] = {{{"file", "worst_Walk.png"}, {"clip", "Walk"}, {"frames", {1, 3, 6}},
                       {"caption", "lbs vs dqs distance at the 3 worst frames"}, {"scale", 0.012}}};
  return report;
}

// BrainStem's size: 20 joints, one clip of 1,047 frames.
json large_report() {
  json report = fixture_report();
  const size_t frames = 1047;
  report["clips"] = {{{"name", "Animation"}, {"frames", frames}, {"fps", 30}, {"times", times(frames, 30)},
                      {"volume", nullptr}, {"worst_frame", 517}, {"image", "worst_Walk.png"}}};
  report["images"][0]["clip"] = "Animation";
  json joints = json::array();
  for (int j = 0; j < 20; ++j) {
    json joint = report["joints"][0];
    joint["joint"] = j;
    joint["name"] = "Bone_" + std::to_string(j);
    joint["summary"]["worst"] = {{"clip", "Animation"}, {"frame", 517}};
    if (j % 3 != 0) joint["verdict"] = {{"code", "lbs-fine"}, {"text", "lbs is fine"}};
    joint["clips"] = {joint_clip("Animation", frames, j == 0, 1)};
    joints.push_back(joint);
  }
  report["joints"] = joints;
  report["verdict"]["joints"] = {"Bone_3"};
  return report;
}

struct ReportPage : ::testing::Test {
  testing_support::ScratchDir scratch{"report_page"};
  std::vector<uint8_t> png = test_png(scratch.path());
  json report = fixture_report();
  std::vector<EmbeddedImage> images = {{"worst_Walk.png", png}};
  std::string page = report_html(report, images);
};

// The <tr> of a joint, up to its </tr>.
std::string row_of(const std::string& page, const std::string& key) {
  const size_t start = page.find("<tr data-joint=\"" + key + "\"");
  if (start == std::string::npos) return "";
  return page.substr(start, page.find("</tr>", start) - start);
}

TEST_F(ReportPage, EscapesEveryStringOfTheDocument) {
  EXPECT_EQ(page.find(kOddName), std::string::npos);
  EXPECT_EQ(page.find("<test>"), std::string::npos);
  EXPECT_EQ(page.find("<fast>"), std::string::npos);
  EXPECT_NE(page.find(">Arm&lt;&amp;\"&gt;'</a>"), std::string::npos);  // text: quotes may stay
  EXPECT_NE(page.find("<title>dqskin report: rig &lt;test&gt;.glb</title>"), std::string::npos);
  EXPECT_NE(page.find("<h4>Run &lt;fast&gt;</h4>"), std::string::npos);

  json hostile = report;
  hostile["input"]["file"] = "<script>alert(1)</script>.glb";
  hostile["images"][0]["caption"] = "\"><img src=x onerror=alert(1)>";
  const std::string other = report_html(hostile, images);
  EXPECT_EQ(other.find("<script"), std::string::npos);
  EXPECT_EQ(other.find("<img src=x"), std::string::npos);
  EXPECT_NE(other.find("alt=\"&quot;&gt;&lt;img src=x onerror=alert(1)&gt;\""), std::string::npos);
}

TEST_F(ReportPage, EveryJointRowCarriesTheJsonNumbersAndShowsThemFormatted) {
  for (const json& joint : report["joints"]) {
    const std::string key = std::to_string(joint["skin"].get<int>()) + ":" + std::to_string(joint["joint"].get<int>());
    const std::string row = row_of(page, key);
    ASSERT_FALSE(row.empty()) << key;
    for (const char* name : {"vertices", "lbs_dib_max", "dqs_dib_max", "candy_wrapper", "dqs_bulge", "twist_max",
                             "bend_max", "flips"}) {
      const json& value = std::string(name) == "vertices" ? joint[name] : joint["summary"][name];
      if (value.is_null()) continue;
      const std::string cell = "data-key=\"" + std::string(name) + "\" data-value=\"" + value.dump() + "\">" +
                               shown_number(value.get<double>()) + "</td>";
      EXPECT_NE(row.find(cell), std::string::npos) << key << ": " << cell;
    }
  }
  // The exact number, not the shown one.
  EXPECT_NE(row_of(page, "0:1").find("data-value=\"0.0123456789\">0.0123</td>"), std::string::npos);
  EXPECT_NE(row_of(page, "0:0").find("data-value=\"2.5e-07\">2.50e-7</td>"), std::string::npos);
  // 0.0123456789 m of a 1.2345 m diagonal.
  EXPECT_NE(row_of(page, "0:1").find("<td class=\"num pct\">1.00 %</td>"), std::string::npos);
}

TEST_F(ReportPage, ShowsNullsAsDashesWithAnEmptyDataValue) {
  const std::string root = row_of(page, "0:0");
  for (const char* name : {"candy_wrapper", "dqs_bulge", "twist_max", "bend_max"})
    EXPECT_NE(root.find("data-key=\"" + std::string(name) + "\" data-value=\"\">\xE2\x80\x93</td>"), std::string::npos) << name;
  EXPECT_EQ(row_of(page, "0:1").find("data-value=\"\""), std::string::npos);
  EXPECT_NE(page.find("No volume"), std::string::npos);  // Run's volume is null
}

TEST_F(ReportPage, EmbedsImagesAsDataUrisOfTheSameBytes) {
  const std::string src = "<img src=\"data:image/png;base64,";
  const size_t at = page.find(src);
  ASSERT_NE(at, std::string::npos);
  const size_t begin = at + src.size(), end = page.find('"', begin);
  std::vector<uint8_t> decoded;
  ASSERT_TRUE(testing_support::base64_decode(std::string_view(page).substr(begin, end - begin), decoded));
  EXPECT_EQ(decoded, png);
  EXPECT_EQ(page.compare(end, 40, "\" data-file=\"worst_Walk.png\" alt=\"lbs vs"), 0);
  EXPECT_NE(page.find("width=\"48\" height=\"24\">", end), std::string::npos);
  EXPECT_EQ(page.find("<img", end), std::string::npos);  // one image, once

  const std::string without = report_html(report, {});
  EXPECT_EQ(without.find("<img"), std::string::npos);
  EXPECT_NE(without.find("worst_Walk.png: not embedded in this page"), std::string::npos);
}

TEST_F(ReportPage, LoadsNothingFromAnywhere) {
  EXPECT_EQ(page.find("<script"), std::string::npos);
  EXPECT_EQ(page.find("<link"), std::string::npos);
  EXPECT_EQ(page.find("url("), std::string::npos);
  EXPECT_EQ(page.find("@import"), std::string::npos);
  for (size_t at = page.find("src=\""); at != std::string::npos; at = page.find("src=\"", at + 1))
    EXPECT_EQ(page.compare(at, 16, "src=\"data:image/"), 0);
  // The only URL is the SVG namespace, which names and loads nothing.
  size_t http = 0;
  for (size_t at = page.find("http"); at != std::string::npos; at = page.find("http", at + 1))
    if (page.compare(at, 26, "http://www.w3.org/2000/svg") != 0 && page.compare(at, 10, "http-equiv") != 0) ++http;
  EXPECT_EQ(http, 0u);
}

TEST_F(ReportPage, IsTheSameBytesForTheSameDocument) {
  EXPECT_EQ(report_html(report, images), page);
  EXPECT_EQ(report_html(json::parse(report.dump()), images), page);  // as read back from report.json
  json changed = report;
  changed["joints"][0]["summary"]["flips"] = 13;
  EXPECT_NE(report_html(changed, images), page);
}

TEST_F(ReportPage, PutsFlaggedJointsFirstAndFoldsTheFineOnes) {
  const size_t arm = page.find("<article class=\"card joint v-add-twist-joints\" id=\"joint-0\"");
  const size_t fold = page.find("<details class=\"fine\"><summary>1 joint where lbs is fine</summary>");
  const size_t root = page.find("<article class=\"card joint v-lbs-fine\" id=\"joint-1\"");
  ASSERT_NE(arm, std::string::npos);
  ASSERT_NE(fold, std::string::npos);
  ASSERT_NE(root, std::string::npos);
  EXPECT_LT(arm, fold);
  EXPECT_LT(fold, root);
  // The table keeps the document's order.
  EXPECT_LT(page.find("data-joint=\"0:1\""), page.find("data-joint=\"0:0\""));
}

TEST_F(ReportPage, ChartsEveryClipOfEveryJoint) {
  size_t charts = 0;
  for (size_t at = page.find("<svg class=\"chart\""); at != std::string::npos; at = page.find("<svg class=\"chart\"", at + 1)) ++charts;
  EXPECT_EQ(charts, 1u + 2 * 2 * 3);  // Walk's volume; 2 joints x 2 clips x 3 charts
  // The root has no cross-section and no parent: its area and angle charts are empty.
  const std::string root = page.substr(page.find("id=\"joint-1\""));
  EXPECT_NE(root.find(">no cross-section</text>"), std::string::npos);
  EXPECT_NE(root.find(">no parent joint</text>"), std::string::npos);
}

TEST_F(ReportPage, MakesAPageOfADamagedDocument) {
  for (const json& damaged : {json(), json::array(), json("text"), json{{"joints", 3}, {"clips", {1, "x", nullptr}}},
                              json{{"joints", {{{"summary", "none"}, {"clips", {{{"series", 1}}}}}}}}}) {
    std::string html;
    EXPECT_NO_THROW(html = report_html(damaged, {})) << damaged.dump();
    EXPECT_NE(html.find("</html>"), std::string::npos);
  }
}

TEST(ReportPageSize, BrainStemSizedReportStaysSmall) {
  testing_support::ScratchDir scratch("report_size");
  const std::string page = report_html(large_report(), {{"worst_Walk.png", test_png(scratch.path())}});
  std::cout << "a 20-joint, 1,047-frame report: " << page.size() << " bytes of HTML\n";
  // 20 joints x 3 charts of at most 600 points per line (2 or 3 lines, ~12 bytes a point).
  EXPECT_LT(page.size(), 1'500'000u);
}

// The pages for the browser check: good/ (the fixture), large/ (BrainStem-sized) and two deliberately
// broken ones, each a report.html beside its report.json and PNG. The breakages are checked here, so that
// the browser check failing on them means it saw them.
TEST_F(ReportPage, WritesThePagesForTheBrowserCheck) {
  std::string wrong_value = page;
  const std::string cell = "data-value=\"0.0123456789\"";
  ASSERT_NE(wrong_value.find(cell), std::string::npos);
  wrong_value.replace(wrong_value.find(cell), cell.size(), "data-value=\"0.0123456\"");
  std::string no_image = page;
  const size_t img = no_image.find("<img ");
  ASSERT_NE(img, std::string::npos);
  no_image.erase(img, no_image.find('>', img) + 1 - img);
  EXPECT_EQ(no_image.find("data-file=\"worst_Walk.png\""), std::string::npos);

  const char* dir = std::getenv("DQSKIN_REPORT_PAGE_DIR");
  // Only report.page_fixture (lib/CMakeLists.txt) sets it; in the ordinary run the pages are made and
  // their breakages checked above, and there is nowhere they are needed.
  if (!dir) return;
  const auto write = [&](const std::string& name, const json& document, const std::string& html) {
    const fs::path folder = fs::path(dir) / name;
    fs::remove_all(folder);
    fs::create_directories(folder);
    std::ofstream(folder / "report.json", std::ios::binary) << document.dump(1);
    std::ofstream(folder / "report.html", std::ios::binary) << html;
    std::ofstream(folder / "worst_Walk.png", std::ios::binary).write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
  };
  write("good", report, page);
  write("large", large_report(), report_html(large_report(), images));
  write("broken_value", report, wrong_value);
  write("broken_image", report, no_image);
}

}  // namespace
}  // namespace dqskin::report_detail
