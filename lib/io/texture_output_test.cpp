#include "dqskin/error.hpp"
#include "dqskin/animation.hpp"
#include "dqskin/load.hpp"
#include "dqskin/texture_output.hpp"
#include "../test_support/scratch_dir.hpp"
#include "../test_support/read_file.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// An EXR read back through OpenImageIO, as a shader's loader would read it.
struct ExrFile {
  OIIO::ImageSpec spec;
  std::vector<float> rgba;  // width × height × 4

  const float* texel(size_t x, size_t y) const { return &rgba[(y * size_t(spec.width) + x) * 4]; }
};

ExrFile read_exr(const fs::path& path) {
  ExrFile exr;
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) {
    ADD_FAILURE() << path << ": " << OIIO::geterror();
    return exr;
  }
  exr.spec = in->spec();
  EXPECT_EQ(exr.spec.nchannels, 4);
  exr.rgba.resize(size_t(exr.spec.width) * size_t(exr.spec.height) * 4);
  EXPECT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, exr.rgba.data())) << in->geterror();
  return exr;
}

using testing_support::read_file;

json read_json(const fs::path& path) { return json::parse(read_file(path)); }

// Bitwise equality, so that -0 ≠ 0 and a NaN would be caught too.
::testing::AssertionResult same_bits(float actual, float expected) {
  if (std::bit_cast<uint32_t>(actual) == std::bit_cast<uint32_t>(expected)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << actual << " != " << expected;
}

// The header a deterministic, lossless 32-bit RGBA texture must have.
void expect_texture_header(const OIIO::ImageSpec& spec) {
  EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(spec.channelnames, (std::vector<std::string>{"R", "G", "B", "A"}));
  for (int c = 0; c < spec.nchannels; ++c) EXPECT_EQ(spec.channelformat(c), OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(spec.get_string_attribute("compression"), "zip");
  EXPECT_EQ(spec.tile_width, 0) << "scanline image";
  EXPECT_EQ(spec.get_string_attribute("DateTime"), "") << "no time stamp (the header holds an empty capDate)";
  EXPECT_EQ(spec.find_attribute("Software"), nullptr);
}

// A clip deformed on the CPU reference, as the frames the writers receive.
struct Deformed {
  Asset asset;
  std::vector<MeshInstance> instances;
  std::vector<double> times;
  DeformedBatch batch;  // every frame
};

Deformed deform_clip(const std::string& path, size_t clip, std::vector<double> times) {
  Deformed d;
  d.asset = load_asset(path);
  d.instances = mesh_instances(d.asset, choose_scene(d.asset, -1));
  d.times = std::move(times);
  std::vector<DeformedFrame> frames;
  for (double t : d.times)
    frames.push_back(deform_frame(d.asset, d.instances, sample_pose(d.asset, &d.asset.clips[clip], t), BlendMode::kDqs));
  d.batch = to_batch(frames, 0);
  return d;
}

// Feeds every frame of `all` to a writer, in order.
void append_all(VatWriter& writer, const DeformedBatch& all) {
  for (size_t f = 0; f < all.frame_count; ++f) writer.append(frame_view(all, f));
}

// Every texel of both images against the frames: vertex v of frame f at (v % W, f·R + v / W), w = 1 for
// positions and 0 for normals, and zeros everywhere else.
void expect_vat_texels(const ExrFile& positions, const ExrFile& normals, const DeformedBatch& batch, size_t wrap) {
  size_t vertices = 0;
  for (const DeformedBatch::Primitive& p : batch.primitives) vertices += p.vertices;
  const size_t w = std::min(vertices, wrap);
  const size_t rows = (vertices + w - 1) / w;
  ASSERT_EQ(size_t(positions.spec.width), w);
  ASSERT_EQ(size_t(positions.spec.height), batch.frame_count * rows);
  ASSERT_EQ(normals.spec.width, positions.spec.width);
  ASSERT_EQ(normals.spec.height, positions.spec.height);
  for (size_t f = 0; f < batch.frame_count; ++f) {
    const FrameView frame = frame_view(batch, f);
    size_t v = 0;
    for (const PrimitiveView& p : frame.primitives) {
      for (size_t k = 0; k < p.vertices; ++k, ++v) {
        const float* pos = positions.texel(v % w, f * rows + v / w);
        const float* nrm = normals.texel(v % w, f * rows + v / w);
        for (size_t c = 0; c < 3; ++c) {
          ASSERT_TRUE(same_bits(pos[c], p.positions[k * 3 + c])) << "frame " << f << " vertex " << v;
          ASSERT_TRUE(same_bits(nrm[c], p.normals.empty() ? 0.0f : p.normals[k * 3 + c])) << "frame " << f << " vertex " << v;
        }
        ASSERT_TRUE(same_bits(pos[3], 1.0f));
        ASSERT_TRUE(same_bits(nrm[3], 0.0f));
      }
    }
    for (; v < w * rows; ++v) {
      for (size_t c = 0; c < 4; ++c) {
        ASSERT_TRUE(same_bits(positions.texel(v % w, f * rows + v / w)[c], 0.0f)) << "padding texel " << v;
        ASSERT_TRUE(same_bits(normals.texel(v % w, f * rows + v / w)[c], 0.0f)) << "padding texel " << v;
      }
    }
  }
}

class TextureOutputTest : public testing::Test {
protected:

  size_t entries() const { return size_t(std::distance(fs::directory_iterator(dir_), fs::directory_iterator())); }

  // Writes the VAT of `d` as clip.{positions,normals}.exr + clip.json in `folder`.
  std::vector<Committed> write_vat(const Deformed& d, const fs::path& folder, size_t wrap,
                                   Overwrite overwrite = Overwrite::kReplace, double fps = 24) {
    VatWriter writer((folder / "clip.positions.exr").string(), (folder / "clip.normals.exr").string(),
                     (folder / "clip.json").string(), vat_sources(d.asset, d.instances), d.times, fps,
                     d.asset.clips[0].name, wrap);
    append_all(writer, d.batch);
    return writer.commit(overwrite);
  }

  const testing_support::ScratchDir scratch_{"texture"};
  const fs::path dir_ = scratch_.path();
};

std::vector<double> grid(size_t frames, double fps) {
  std::vector<double> t;
  for (size_t i = 0; i < frames; ++i) t.push_back(double(i) / fps);
  return t;
}

TEST_F(TextureOutputTest, VatTexelsAreTheFramesBitForBit) {
  const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf", 0, grid(9, 8));
  EXPECT_EQ(write_vat(d, dir_, kVatMaxWidth),
            (std::vector<Committed>{Committed::kWritten, Committed::kWritten, Committed::kWritten}));
  const ExrFile positions = read_exr(dir_ / "clip.positions.exr");
  const ExrFile normals = read_exr(dir_ / "clip.normals.exr");
  expect_texture_header(positions.spec);
  expect_texture_header(normals.spec);
  EXPECT_EQ(positions.spec.width, 216) << "both instances' vertices in one row";
  expect_vat_texels(positions, normals, d.batch, kVatMaxWidth);
  EXPECT_EQ(entries(), 3u) << "no temporaries left behind";
}

TEST_F(TextureOutputTest, VatWrapsLongRowsAndPadsWithZeros) {
  // 216 vertices in rows of 10: 22 rows per frame, the last with 6 vertices and 4 zero texels; the
  // second instance's vertices start mid-row.
  const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf", 0, grid(5, 4));
  write_vat(d, dir_, 10);
  const ExrFile positions = read_exr(dir_ / "clip.positions.exr");
  const ExrFile normals = read_exr(dir_ / "clip.normals.exr");
  EXPECT_EQ(positions.spec.width, 10);
  EXPECT_EQ(positions.spec.height, 5 * 22);
  expect_vat_texels(positions, normals, d.batch, 10);
  const json side = read_json(dir_ / "clip.json");
  EXPECT_EQ(side["wrap_width"], 10);
  EXPECT_EQ(side["rows_per_frame"], 22);
  EXPECT_EQ(side["height"], 110);
}

TEST_F(TextureOutputTest, VatLayoutOfHandMadeFrames) {
  // Two primitives (3 vertices with normals, 2 without) in rows of 2: three rows per frame, texel (1, 2)
  // is padding. Values are chosen so that every texel says where it came from.
  DeformedBatch batch;
  batch.frame_count = 2;
  batch.primitives.resize(2);
  batch.primitives[0].vertices = 3;
  batch.primitives[1].vertices = 2;
  for (size_t f = 0; f < 2; ++f) {
    for (size_t i = 0; i < 2; ++i) {
      DeformedBatch::Primitive& p = batch.primitives[i];
      for (size_t v = 0; v < p.vertices; ++v) {
        for (size_t c = 0; c < 3; ++c) {
          p.positions.push_back(float(100 * f + 10 * i + v) + 0.25f * float(c));
          if (i == 0) p.normals.push_back(-float(100 * f + v) - 0.5f * float(c));
        }
      }
    }
  }
  std::vector<VatSource> sources = {{0, 0, 0, 3, "a", "m"}, {1, 1, 0, 2, "b", "n"}};
  {
    VatWriter writer((dir_ / "p.exr").string(), (dir_ / "n.exr").string(), (dir_ / "v.json").string(), sources,
                     {0.0, 0.75}, 0, "hand", 2);
    writer.append(frame_view(batch, 0));
    writer.append(frame_view(batch, 1));
    writer.commit(Overwrite::kReplace);
  }
  const ExrFile p = read_exr(dir_ / "p.exr");
  const ExrFile n = read_exr(dir_ / "n.exr");
  ASSERT_EQ(p.spec.width, 2);
  ASSERT_EQ(p.spec.height, 6);
  // Frame 1, primitive 1, vertex 0 is vertex 3 of the frame: texel (1, 1·3 + 1).
  EXPECT_EQ(std::vector<float>(p.texel(1, 4), p.texel(1, 4) + 4), (std::vector<float>{110, 110.25f, 110.5f, 1}));
  EXPECT_EQ(std::vector<float>(n.texel(1, 4), n.texel(1, 4) + 4), (std::vector<float>{0, 0, 0, 0}));
  // Frame 0, vertex 2 (primitive 0): texel (0, 1), its normal too.
  EXPECT_EQ(std::vector<float>(p.texel(0, 1), p.texel(0, 1) + 4), (std::vector<float>{2, 2.25f, 2.5f, 1}));
  EXPECT_EQ(std::vector<float>(n.texel(0, 1), n.texel(0, 1) + 4), (std::vector<float>{-2, -2.5f, -3, 0}));
  expect_vat_texels(p, n, batch, 2);

  const json side = read_json(dir_ / "v.json");
  EXPECT_TRUE(side["fps"].is_null()) << "times that are not a grid have no fps";
  EXPECT_EQ(side["frame_times"], json::parse("[0.0, 0.75]"));
  EXPECT_EQ(side["bounds"]["min"], json::parse("[0.0, 0.25, 0.5]"));
  EXPECT_EQ(side["bounds"]["max"], json::parse("[111.0, 111.25, 111.5]"));
  EXPECT_EQ(side["sources"][1]["first_vertex"], 3);
}

TEST_F(TextureOutputTest, VatSideFileDescribesTheTextures) {
  const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf", 0, grid(4, 3));
  write_vat(d, dir_, kVatMaxWidth, Overwrite::kReplace, 3);
  const json side = read_json(dir_ / "clip.json");
  EXPECT_EQ(side["clip"], d.asset.clips[0].name);
  EXPECT_EQ(side["vertex_count"], 216);
  EXPECT_EQ(side["frame_count"], 4);
  EXPECT_EQ(side["fps"], 3.0);
  ASSERT_EQ(side["frame_times"].size(), 4u);
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(side["frame_times"][i].get<double>(), d.times[i]);
  EXPECT_EQ(side["wrap_width"], 216);
  EXPECT_EQ(side["rows_per_frame"], 1);
  EXPECT_EQ(side["width"], 216);
  EXPECT_EQ(side["height"], 4);
  EXPECT_EQ(side["attributes"]["positions"]["file"], "clip.positions.exr");
  EXPECT_EQ(side["attributes"]["normals"]["file"], "clip.normals.exr");

  // The bounding box is over every vertex of every frame, exactly (the floats in the texture).
  float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (const DeformedBatch::Primitive& p : d.batch.primitives) {
    for (size_t i = 0; i < p.positions.size(); ++i) {
      lo[i % 3] = std::min(lo[i % 3], p.positions[i]);
      hi[i % 3] = std::max(hi[i % 3], p.positions[i]);
    }
  }
  for (size_t c = 0; c < 3; ++c) {
    EXPECT_EQ(side["bounds"]["min"][c].get<float>(), lo[c]);
    EXPECT_EQ(side["bounds"]["max"][c].get<float>(), hi[c]);
  }

  // Sources: both instances in scene order, each with its one primitive, covering the vertices in order.
  const std::vector<VatSource> sources = vat_sources(d.asset, d.instances);
  ASSERT_EQ(side["sources"].size(), sources.size());
  ASSERT_EQ(sources.size(), 2u);
  size_t first = 0;
  for (size_t i = 0; i < sources.size(); ++i) {
    const json& s = side["sources"][i];
    EXPECT_EQ(s["node"], d.instances[i].node);
    EXPECT_EQ(s["node_name"], d.asset.nodes[size_t(d.instances[i].node)].name);
    EXPECT_EQ(s["mesh"], d.instances[i].mesh);
    EXPECT_EQ(s["mesh_name"], d.asset.meshes[size_t(d.instances[i].mesh)].name);
    EXPECT_EQ(s["primitive"], 0);
    EXPECT_EQ(s["first_vertex"], first);
    EXPECT_EQ(s["vertex_count"], 108);
    first += 108;
  }
}

TEST_F(TextureOutputTest, VatOutputsAreByteIdenticalWhateverTheThreadCount) {
  // Rows of 10 give 22 rows per frame, so the images span many 16-row ZIP blocks that OpenEXR compresses
  // on its thread pool when it has one.
  const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf", 0, grid(12, 11));
  int threads = 0;
  OIIO::getattribute("exr_threads", threads);
  fs::create_directories(dir_ / "a");
  fs::create_directories(dir_ / "b");
  fs::create_directories(dir_ / "c");
  OIIO::attribute("exr_threads", 1);
  write_vat(d, dir_ / "a", 10);
  OIIO::attribute("exr_threads", 8);
  write_vat(d, dir_ / "b", 10);
  OIIO::attribute("exr_threads", threads);
  sleep(1);  // a time stamp would now differ
  write_vat(d, dir_ / "c", 10);
  for (const char* name : {"clip.positions.exr", "clip.normals.exr", "clip.json"}) {
    const std::string a = read_file(dir_ / "a" / name);
    EXPECT_FALSE(a.empty());
    EXPECT_EQ(a, read_file(dir_ / "b" / name)) << name;
    EXPECT_EQ(a, read_file(dir_ / "c" / name)) << name;
  }
}

TEST_F(TextureOutputTest, VatRefuseDifferentKeepsEqualFilesAndChangesNoneWhenOneDiffers) {
  const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf", 0, grid(3, 2));
  write_vat(d, dir_, kVatMaxWidth);
  const std::string positions = read_file(dir_ / "clip.positions.exr");
  const std::string json_text = read_file(dir_ / "clip.json");
  EXPECT_EQ(write_vat(d, dir_, kVatMaxWidth, Overwrite::kRefuseDifferent),
            (std::vector<Committed>{Committed::kUnchanged, Committed::kUnchanged, Committed::kUnchanged}));
  // Same images, another fps: only the JSON differs, and nothing is renamed, the images included.
  fs::remove(dir_ / "clip.normals.exr");
  try {
    write_vat(d, dir_, kVatMaxWidth, Overwrite::kRefuseDifferent, 50);
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()), (dir_ / "clip.json").string() + ": exists with different contents; not overwritten");
  }
  EXPECT_FALSE(fs::exists(dir_ / "clip.normals.exr")) << "refused before any rename";
  EXPECT_EQ(read_file(dir_ / "clip.positions.exr"), positions);
  EXPECT_EQ(read_file(dir_ / "clip.json"), json_text);
  EXPECT_EQ(entries(), 2u);
}

TEST_F(TextureOutputTest, UncommittedVatWriterLeavesNoFiles) {
  const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf", 0, grid(4, 4));
  {
    VatWriter writer((dir_ / "x.positions.exr").string(), (dir_ / "x.normals.exr").string(),
                     (dir_ / "x.json").string(), vat_sources(d.asset, d.instances), d.times, 4, "sway");
    writer.append(frame_view(d.batch, 0));
    writer.append(frame_view(d.batch, 1));
    EXPECT_THROW(writer.commit(Overwrite::kReplace), std::logic_error) << "two frames are missing";
  }
  EXPECT_EQ(entries(), 0u);
}

TEST_F(TextureOutputTest, VatUnwritableFolderIsAnOutputErrorNamingTheFile) {
  const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf", 0, grid(1, 1));
  const fs::path missing = dir_ / "missing";
  try {
    VatWriter writer((dir_ / "p.exr").string(), (missing / "n.exr").string(), (dir_ / "v.json").string(),
                     vat_sources(d.asset, d.instances), d.times, 1, "sway");
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind((missing / "n.exr").string() + ": ", 0), 0u) << e.what();
  }
  EXPECT_EQ(entries(), 0u) << "the positions temporary is removed too";
}

// Bone textures of every frame of a clip of `file`'s skin 0, written and read back.
struct BonesCase {
  Asset asset;
  std::vector<double> times;
  BoneTexture texture;
};

BonesCase bones_of(const std::string& path, std::vector<double> times) {
  BonesCase b;
  b.asset = load_asset(path);
  b.times = std::move(times);
  std::vector<JointTransforms> frames;
  for (double t : b.times) frames.push_back(joint_transforms(b.asset.skins[0], sample_pose(b.asset, &b.asset.clips[0], t)));
  b.texture = pack_bone_texture(frames);
  return b;
}

void expect_bone_texture(const fs::path& exr, const BoneTexture& texture) {
  const ExrFile image = read_exr(exr);
  expect_texture_header(image.spec);
  ASSERT_EQ(size_t(image.spec.width), texture.width());
  ASSERT_EQ(size_t(image.spec.height), texture.frames);
  ASSERT_EQ(image.rgba.size(), texture.rgba.size());
  for (size_t i = 0; i < image.rgba.size(); ++i) ASSERT_TRUE(same_bits(image.rgba[i], texture.rgba[i])) << "float " << i;
}

TEST_F(TextureOutputTest, BoneTextureIsTheRgbaBitForBit) {
  for (const char* rig : {"bending_arm.gltf", "nonuniform_scale.gltf"}) {
    SCOPED_TRACE(rig);
    const BonesCase b = bones_of(std::string(DQSKIN_TESTDATA_DIR) + "/" + rig, grid(7, 6));
    EXPECT_EQ(b.texture.texels_per_joint, std::string(rig) == "bending_arm.gltf" ? 2 : 5);
    const fs::path exr = dir_ / (std::string(rig) + ".bones.exr");
    const fs::path side = dir_ / (std::string(rig) + ".bones.json");
    EXPECT_EQ(write_bone_texture(exr.string(), side.string(), b.texture, b.asset, 0, b.times, 6, Overwrite::kReplace),
              (std::vector<Committed>{Committed::kWritten, Committed::kWritten}));
    expect_bone_texture(exr, b.texture);

    const json j = read_json(side);
    const Skin& skin = b.asset.skins[0];
    EXPECT_EQ(j["skin"], 0);
    EXPECT_EQ(j["skin_name"], skin.name);
    ASSERT_EQ(j["joints"].size(), skin.joints.size());
    for (size_t i = 0; i < skin.joints.size(); ++i) EXPECT_EQ(j["joints"][i], b.asset.nodes[size_t(skin.joints[i])].name);
    EXPECT_EQ(j["texels_per_joint"], b.texture.texels_per_joint);
    EXPECT_EQ(j["frame_count"], 7);
    EXPECT_EQ(j["fps"], 6.0);
    for (size_t i = 0; i < b.times.size(); ++i) EXPECT_EQ(j["frame_times"][i].get<double>(), b.times[i]);
    EXPECT_EQ(j["file"], exr.filename().string());

    // Written again: the same bytes, and under kRefuseDifferent nothing to do.
    const std::string first = read_file(exr);
    EXPECT_EQ(write_bone_texture(exr.string(), side.string(), b.texture, b.asset, 0, b.times, 6,
                                 Overwrite::kRefuseDifferent),
              (std::vector<Committed>{Committed::kUnchanged, Committed::kUnchanged}));
    EXPECT_EQ(read_file(exr), first);
  }
  EXPECT_EQ(entries(), 4u);
}

TEST_F(TextureOutputTest, BoneTextureUnwritableFolderIsAnOutputErrorNamingTheFile) {
  const BonesCase b = bones_of(std::string(DQSKIN_TESTDATA_DIR) + "/bending_arm.gltf", grid(2, 2));
  const fs::path exr = dir_ / "missing" / "bones.exr";
  try {
    write_bone_texture(exr.string(), (dir_ / "bones.json").string(), b.texture, b.asset, 0, b.times, 2,
                       Overwrite::kReplace);
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(exr.string() + ": ", 0), 0u) << e.what();
  }
  EXPECT_EQ(entries(), 0u);
}

// The shared sample models (../shared/testdata): the first clip of each, eight frames spread over it,
// through the VAT writer (rows of 1000, so the larger models wrap) and, for skinned models, the bone
// texture of skin 0.
class SharedModelTextures : public TextureOutputTest, public testing::WithParamInterface<const char*> {};

TEST_P(SharedModelTextures, RoundTripOneClip) {
  const fs::path path = fs::path(DQSKIN_SHARED_TESTDATA_DIR) / GetParam();
  if (!fs::exists(path)) GTEST_SKIP() << "shared test data not found: " << path;
  const Asset probe = load_asset(path.string());
  const std::vector<double> all = frame_times(probe.clips[0], FrameSpec{});
  std::vector<double> times;
  for (size_t i = 0; i < 8; ++i) times.push_back(all[i * (all.size() - 1) / 7]);
  const Deformed d = deform_clip(path.string(), 0, times);
  write_vat(d, dir_, 1000, Overwrite::kReplace, 0);
  expect_vat_texels(read_exr(dir_ / "clip.positions.exr"), read_exr(dir_ / "clip.normals.exr"), d.batch, 1000);
  if (!d.asset.skins.empty()) {
    const BonesCase b = bones_of(path.string(), times);
    write_bone_texture((dir_ / "bones.exr").string(), (dir_ / "bones.json").string(), b.texture, b.asset, 0, b.times, 0,
                       Overwrite::kReplace);
    expect_bone_texture(dir_ / "bones.exr", b.texture);
  }
}

INSTANTIATE_TEST_SUITE_P(Models, SharedModelTextures,
                         testing::Values("RiggedSimple/RiggedSimple.glb", "RiggedFigure/RiggedFigure.glb",
                                         "CesiumMan/CesiumMan.glb", "SimpleSkin/SimpleSkin.gltf", "Fox/Fox.glb",
                                         "BrainStem/BrainStem.glb", "RecursiveSkeletons/RecursiveSkeletons.glb",
                                         "raylib_robot/robot.glb", "raylib_greenman/greenman.glb",
                                         "InterpolationTest/InterpolationTest.glb",
                                         "AnimatedMorphCube/AnimatedMorphCube.glb", "SimpleMorph/SimpleMorph.gltf"),
                         [](const testing::TestParamInfo<const char*>& model) {
                           std::string name = fs::path(model.param).stem().string();
                           for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return name;
                         });

}  // namespace
}  // namespace dqskin
