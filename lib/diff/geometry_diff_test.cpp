// The geometric diff: clip pairing and animation findings on built assets, and whole diffs of the rigs
// (on the fast CPU deformer, so no GL context is needed).
#include "clip_matching.hpp"

#include "dqskin/error.hpp"
#include "dqskin/geometry_diff.hpp"
#include "dqskin/geometry_report.hpp"
#include "../test_support/scratch_dir.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace dqskin {
namespace {

using diff_detail::ClipMatch;
using diff_detail::comparison_times;
using diff_detail::match_clips;

Asset with_clips(std::vector<std::string> names) {
  Asset asset;
  asset.nodes.resize(2);
  asset.nodes[1].name = "elbow";
  for (const std::string& name : names) {
    Clip clip;
    clip.name = name;
    Channel c;
    c.node = 1;
    c.path = TargetPath::kRotation;
    c.times = {0.0f, 1.0f};
    c.values.assign(8, 0.0f);
    c.components = 4;
    clip.channels.push_back(c);
    clip.last_key = 1;
    asset.clips.push_back(clip);
  }
  return asset;
}

size_t count(const std::vector<AnimationFinding>& findings, DiffStatus severity) {
  size_t n = 0;
  for (const AnimationFinding& f : findings) n += f.severity == severity;
  return n;
}

TEST(ClipMatching, PairsByNameThenByIndexAndReportsTheRest) {
  const Asset a = with_clips({"Walk", "Run", "Idle"});
  const Asset b = with_clips({"Run", "Jump", "Walk", "Extra"});
  const ClipMatch m = match_clips(a, b, {0, 1, 2});
  ASSERT_EQ(m.pairs.size(), 2u);
  EXPECT_EQ(m.pairs[0].a, 0);
  EXPECT_EQ(m.pairs[0].b, 2);  // Walk by name
  EXPECT_EQ(m.pairs[1].b, 0);  // Run by name
  // Idle's index (2) is Walk's, already paired: Idle is missing (a failure), Jump and Extra are extra.
  EXPECT_EQ(count(m.findings, DiffStatus::kFail), 1u);
  EXPECT_EQ(count(m.findings, DiffStatus::kWarn), 2u);
}

TEST(ClipMatching, RenamedClipsPairByIndexWithANote) {
  const ClipMatch m = match_clips(with_clips({"Walk", "Take 001"}), with_clips({"Walk", "Armature|Take"}), {0, 1});
  ASSERT_EQ(m.pairs.size(), 2u);
  EXPECT_EQ(m.pairs[1].b, 1);
  ASSERT_EQ(m.findings.size(), 1u);
  EXPECT_EQ(m.findings[0].severity, DiffStatus::kPass);
  EXPECT_NE(m.findings[0].text.find("Armature|Take"), std::string::npos);
}

TEST(ClipMatching, NothingInCommonIsAnInputError) {
  EXPECT_THROW(match_clips(with_clips({"Walk"}), Asset{}, {0}), InputError);
  // Neither file animates: the rest pose is compared.
  const ClipMatch rest = match_clips(Asset{}, Asset{}, {});
  ASSERT_EQ(rest.pairs.size(), 1u);
  EXPECT_EQ(rest.pairs[0].a, -1);
}

TEST(AnimationFindings, NameDroppedChannelsAndChangedKeys) {
  const Asset a = with_clips({"Walk"});
  Asset b = with_clips({"Walk"});
  b.clips[0].channels[0].times = {0.0f, 0.5f, 1.25f};
  b.clips[0].channels[0].values.assign(12, 0.0f);
  b.clips[0].last_key = 1.25;
  Channel moved = b.clips[0].channels[0];
  moved.path = TargetPath::kTranslation;
  b.clips[0].channels.push_back(moved);
  const auto notes = diff_detail::compare_animations(a, a.clips[0], b, b.clips[0], "Walk");
  std::string all;
  for (const AnimationFinding& f : notes) all += f.text + "\n";
  EXPECT_NE(all.find("duration 1 s in A, 1.25 s in B"), std::string::npos) << all;
  EXPECT_NE(all.find("channel elbow rotation: 2 keys in A, 3 in B"), std::string::npos) << all;
  EXPECT_NE(all.find("channel elbow translation in B only"), std::string::npos) << all;
  EXPECT_EQ(count(notes, DiffStatus::kPass), notes.size());  // notes never fail a diff by themselves
}

TEST(ComparisonTimes, AreTheKeysOfBothAndTheMidpoints) {
  Clip a, b;
  a.channels.resize(1);
  b.channels.resize(1);
  a.channels[0].times = {0.0f, 1.0f};
  b.channels[0].times = {0.0f, 0.5f, 1.000001f};  // the last key is a's, rounded differently
  EXPECT_EQ(comparison_times(&a, &b), (std::vector<double>{0.0, 0.25, 0.5, 0.75, 1.0}));
  EXPECT_EQ(comparison_times(nullptr, nullptr), std::vector<double>{0.0});
}

GeometryDiffOptions cpu_options() {
  GeometryDiffOptions o;
  o.backend = Backend::kFastCpu;
  o.threads = 2;
  return o;
}

const std::string kArm = std::string(DQSKIN_TESTDATA_DIR) + "/bending_arm.gltf";

TEST(GeometryDiff, AFileAgainstItselfIsTheIdentityWithErrorZero) {
  const GeometryDiffReport r = diff_geometry(kArm, kArm, cpu_options());
  EXPECT_TRUE(r.identity);
  ASSERT_EQ(r.clips.size(), 1u);
  const ClipGeometryDiff& c = r.clips[0];
  EXPECT_EQ(c.name, "bend");
  EXPECT_EQ(c.max_error, 0.0);
  EXPECT_EQ(c.max_normal_degrees, 0.0);
  EXPECT_EQ(c.status, DiffStatus::kPass);
  EXPECT_GT(c.frames.size(), 2u);
  EXPECT_GT(c.diagonal, 4.0);  // the arm is 4 long
  EXPECT_EQ(r.status(), DiffStatus::kPass);
}

// A copy of a file with its root moved: `by` along +y.
std::string moved_copy(const testing_support::ScratchDir& dir, double by) {
  nlohmann::json doc;
  std::ifstream(kArm) >> doc;
  // The buffers are data URIs, so the copy stands alone.
  for (size_t root = 0; root < 2; ++root) doc["nodes"][root]["translation"] = {0.0, by, 0.0};
  const std::string path = (dir.path() / "moved.gltf").string();
  std::ofstream(path) << doc.dump();
  return path;
}

TEST(GeometryDiff, ARigidMoveIsMeasuredAtEveryFrame) {
  const testing_support::ScratchDir dir("geometry_diff");
  GeometryDiffOptions o = cpu_options();
  o.thresholds.fail = 0.5;
  o.thresholds.warn = 0.001;
  const GeometryDiffReport r = diff_geometry(kArm, moved_copy(dir, 0.01), o);
  EXPECT_FALSE(r.identity);
  const ClipGeometryDiff& c = r.clips[0];
  // At rest every vertex is at most the move from the moved surface, and those on the faces turned ±y
  // exactly the move. Animated, each vertex follows its closest point at rest, which on a bending tube is
  // not the same material point: the error grows, but stays of the move's size.
  EXPECT_NEAR(r.rest_a_to_b, 0.01, 1e-6);
  EXPECT_GE(c.max_error, 0.01 - 1e-6);
  EXPECT_LT(c.max_error, 0.02);
  EXPECT_EQ(c.status, DiffStatus::kWarn);
  EXPECT_NE(c.reason.find("over --warn"), std::string::npos) << c.reason;
  const std::string text = geometry_text(r);
  EXPECT_NE(text.find("WARN  clip bend, t = "), std::string::npos) << text;
}

// The reports hold nothing of the run: the same files give the same bytes, on any number of threads.
TEST(GeometryDiff, ReportsAreTheSameBytesRunAfterRunAndThreadsApart) {
  const testing_support::ScratchDir dir("geometry_diff");
  const std::string moved = moved_copy(dir, 0.01);
  GeometryDiffOptions one = cpu_options(), two = cpu_options();
  one.threads = 1;
  const GeometryDiffReport first = diff_geometry(kArm, moved, one), second = diff_geometry(kArm, moved, two);
  EXPECT_EQ(geometry_json(first), geometry_json(second));
  EXPECT_EQ(geometry_text(first), geometry_text(second));
  EXPECT_EQ(geometry_junit(first), geometry_junit(second));
}

// Problems of the pair, not of either file, name both files.
TEST(GeometryDiff, SurfacesThatDoNotOverlapAreAnInputErrorNamingBothFiles) {
  const testing_support::ScratchDir dir("geometry_diff");
  const std::string moved = moved_copy(dir, 100.0);
  try {
    diff_geometry(kArm, moved, cpu_options());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(kArm + " vs " + moved + ": the two files' meshes do not overlap", 0), 0u)
        << e.what();
  }
}

TEST(GeometryDiff, NoClipInCommonIsAnInputErrorNamingBothFiles) {
  const testing_support::ScratchDir dir("geometry_diff");
  nlohmann::json doc;
  std::ifstream(kArm) >> doc;
  doc.erase("animations");
  const std::string still = (dir.path() / "still.gltf").string();
  std::ofstream(still) << doc.dump();
  try {
    diff_geometry(kArm, still, cpu_options());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), kArm + " vs " + still + ": no clip in common: A has bend; B has no animations");
  }
}

// Each file goes through the loader's every check, and the message names the file that failed.
TEST(GeometryDiff, AMalformedFileOnEitherSideIsAnInputErrorNamingIt) {
  const testing_support::ScratchDir dir("geometry_diff");
  nlohmann::json doc;
  std::ifstream(kArm) >> doc;
  doc["accessors"][0]["count"] = 100000;  // more positions than the buffer view holds
  const std::string bad = (dir.path() / "bad.gltf").string();
  std::ofstream(bad) << doc.dump();
  for (const auto& [a, b] : {std::pair{kArm, bad}, std::pair{bad, kArm}}) {
    try {
      diff_geometry(a, b, cpu_options());
      FAIL() << "no error";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(bad + ": ", 0), 0u) << e.what();
    }
  }
}

TEST(GeometryDiff, RelativeThresholdsScaleWithTheDiagonal) {
  const testing_support::ScratchDir dir("geometry_diff");
  GeometryDiffOptions o = cpu_options();
  o.relative = true;
  o.thresholds.fail = o.thresholds.warn = 0.03 / 4.0;  // errors are under 0.02, the diagonal a little over 4
  EXPECT_EQ(diff_geometry(kArm, moved_copy(dir, 0.01), o).status(), DiffStatus::kPass);
  o.thresholds.fail = o.thresholds.warn = 0.001 / 4.0;
  EXPECT_EQ(diff_geometry(kArm, moved_copy(dir, 0.01), o).status(), DiffStatus::kFail);
}

// Two bake folders of OBJ frames written here: per vertex, missing and mismatched files fail.
TEST(BakeDiff, PairsFilesByPathAndComparesVertexByVertex) {
  const testing_support::ScratchDir dir("bake_diff");
  auto write = [&](const std::string& name, const std::string& text) {
    std::filesystem::create_directories((dir.path() / name).parent_path());
    std::ofstream(dir.path() / name) << text;
  };
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 2 0\nf 1 2 3\n";
  for (const char* side : {"a", "b"}) write(std::string(side) + "/manifest.json", "{}");
  write("a/m/walk/frame_0000.obj", tri);
  write("b/m/walk/frame_0000.obj", tri);
  write("a/m/walk/frame_0001.obj", tri);
  write("b/m/walk/frame_0001.obj", "v 0 0 0\nv 1 0.5 0\nv 0 2 0\nf 1 2 3\n");
  write("a/m/walk/frame_0002.obj", tri);
  write("b/m/walk/frame_0002.obj", "v 0 0 0\nv 1 0 0\nf 1 2 2\n");
  write("a/m/walk/frame_0003.obj", tri);
  write("a/m/walk/notes.txt", "not a frame");
  const std::string a = (dir.path() / "a").string(), b = (dir.path() / "b").string();
  EXPECT_TRUE(is_bake_folder(a));
  EXPECT_FALSE(is_bake_folder(a + "/m"));
  GeometryDiffOptions o;
  o.thresholds.fail = 0.1;
  const GeometryDiffReport r = diff_bakes(a, b, o);
  ASSERT_EQ(r.clips.size(), 4u);  // notes.txt is not a frame
  EXPECT_EQ(r.clips[0].name, "m/walk/frame_0000.obj");
  EXPECT_EQ(r.clips[0].status, DiffStatus::kPass);
  EXPECT_EQ(r.clips[1].status, DiffStatus::kFail);
  EXPECT_FLOAT_EQ(float(r.clips[1].max_error), 0.5f);
  EXPECT_EQ(r.clips[1].worst.vertex, 1u);
  EXPECT_NE(r.clips[1].reason.find("1 vertices (33.3%) over --fail 0.1"), std::string::npos) << r.clips[1].reason;
  EXPECT_EQ(r.clips[2].status, DiffStatus::kFail);
  EXPECT_EQ(r.clips[2].reason, "3 vertices or texels in A, 2 in B");
  EXPECT_EQ(r.clips[3].reason, "missing in B");
  EXPECT_EQ(r.status(), DiffStatus::kFail);
  EXPECT_NE(geometry_text(r).find("FAIL  m/walk/frame_0001.obj, max 50 cm at vertex 1"), std::string::npos)
      << geometry_text(r);
}

// A frame that is a symbolic link may name any file: the diff would read it and quote it in its report.
TEST(BakeDiff, RefusesASymbolicLinkInABakeFolderNamingIt) {
  const testing_support::ScratchDir dir("bake_diff");
  std::ofstream(dir.path() / "secret.txt") << "v 1 2 3\n";
  for (const char* side : {"a", "b"}) {
    std::filesystem::create_directories(dir.path() / side / "m");
    std::ofstream(dir.path() / side / "manifest.json") << "{}";
    std::filesystem::create_symlink("../../secret.txt", dir.path() / side / "m" / "frame_0000.obj");
  }
  const std::string a = (dir.path() / "a").string(), b = (dir.path() / "b").string();
  try {
    diff_bakes(a, b, {});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), a + "/m/frame_0000.obj: is a symbolic link, which diff does not follow in a bake folder");
  }
}

}  // namespace
}  // namespace dqskin
