// The VAT writer in every profile: texels where the layout says, side files that say what they hold, and
// the decode-back round trip within the error each encoding allows (asserted, not printed).
#include "vat_check.hpp"
#include "vat_measure.hpp"
#include "vat_writer.hpp"
#include "rest_glb.hpp"

#include "dqskin/animation.hpp"
#include "dqskin/error.hpp"
#include "dqskin/load.hpp"
#include "texture_output.hpp"
#include "../test_support/read_file.hpp"
#include "../test_support/scratch_dir.hpp"
#include "../test_support/test_models.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>

namespace dqskin::texture {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing_support::read_file;

// An image read back through OpenImageIO as floats (integers as their values), as a loader would.
struct Image {
  OIIO::ImageSpec spec;
  std::vector<float> texels;
  const float* texel(size_t x, size_t y) const { return &texels[(y * size_t(spec.width) + x) * size_t(spec.nchannels)]; }
};

Image read_image(const fs::path& path) {
  Image image;
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) {
    ADD_FAILURE() << path << ": " << OIIO::geterror();
    return image;
  }
  image.spec = in->spec();
  image.texels.resize(size_t(image.spec.width) * size_t(image.spec.height) * size_t(image.spec.nchannels));
  // Integer PNGs come back as their integer values (not scaled to [0, 1]) through a float conversion of
  // the stored type: read as the stored type first.
  if (image.spec.format == OIIO::TypeDesc::UINT8 || image.spec.format == OIIO::TypeDesc::UINT16) {
    std::vector<uint16_t> raw(image.texels.size());
    EXPECT_TRUE(in->read_image(0, 0, 0, image.spec.nchannels, OIIO::TypeDesc::UINT16, raw.data()));
    const float scale = image.spec.format == OIIO::TypeDesc::UINT8 ? 257.0f : 1.0f;  // 8 bits widen by ×257
    for (size_t i = 0; i < raw.size(); ++i) image.texels[i] = float(raw[i]) / scale;
  } else {
    EXPECT_TRUE(in->read_image(0, 0, 0, image.spec.nchannels, OIIO::TypeDesc::FLOAT, image.texels.data()));
  }
  return image;
}

json read_json(const fs::path& path) { return json::parse(read_file(path)); }

::testing::AssertionResult same_bits(float actual, float expected) {
  if (std::bit_cast<uint32_t>(actual) == std::bit_cast<uint32_t>(expected)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << actual << " != " << expected;
}

// A clip deformed on the CPU reference: its frames, the midpoints between them, and the rest pose.
struct Deformed {
  Asset asset;
  std::vector<MeshInstance> instances;
  std::vector<double> times;
  DeformedBatch frames, midpoints, rest;
};

DeformedBatch deform_at(const Deformed& d, const Clip* clip, const std::vector<double>& times) {
  std::vector<DeformedFrame> frames;
  for (double t : times) frames.push_back(deform_frame(d.asset, d.instances, sample_pose(d.asset, clip, t), BlendMode::kDqs));
  return to_batch(frames, 0);
}

Deformed deform_clip(const std::string& path, size_t clip, std::vector<double> times) {
  Deformed d;
  d.asset = load_asset(path);
  d.instances = mesh_instances(d.asset, choose_scene(d.asset, -1));
  d.times = std::move(times);
  const Clip* c = d.asset.clips.empty() ? nullptr : &d.asset.clips[clip];
  d.frames = deform_at(d, c, d.times);
  std::vector<double> mid;
  for (size_t i = 0; i + 1 < d.times.size(); ++i) mid.push_back((d.times[i] + d.times[i + 1]) / 2);
  if (!mid.empty()) d.midpoints = deform_at(d, c, mid);
  d.rest = deform_at(d, nullptr, {0.0});
  return d;
}

std::vector<double> grid(size_t frames, double fps) {
  std::vector<double> t;
  for (size_t i = 0; i < frames; ++i) t.push_back(double(i) / fps);
  return t;
}

size_t vertex_count(const Deformed& d) {
  size_t n = 0;
  for (const DeformedBatch::Primitive& p : d.frames.primitives) n += p.vertices;
  return n;
}

// What a bake of one clip does with the writer: measure, write, read back and check, commit.
struct Written {
  VatEncoding encoding;
  DecodeCheck check;
  double reference_motion = 0, decoded_motion = 0;
  VatFileNames names;
};

Written write_clip(const Deformed& d, const VatFormat& format, const fs::path& folder, size_t max_size = 0, bool pot = false,
                   const VatLayout* layout = nullptr, Overwrite overwrite = Overwrite::kReplace, double fps = 24) {
  VatEncoding e;
  e.layout = layout ? *layout : plan_vat_layout(format, vertex_count(d), d.times.size(), max_size, pot, "test");
  if (format.profile == VatProfile::kOpenVat) e.rest = all_positions(frame_view(d.rest, 0));
  VatClipInfo info;
  info.asset = "rig";
  info.clip = d.asset.clips.empty() ? "rest" : d.asset.clips[0].name;
  info.times = d.times;
  info.fps = fps;
  info.sources = vat_sources(d.asset, d.instances);
  VatMeasure measure(e);
  for (size_t f = 0; f < d.times.size(); ++f) measure.add(frame_view(d.frames, f), f, d.times.size());
  measure.finish(info, "test");
  const VatFileNames names = vat_file_names(format, "rig");
  const FrameView rest = format.profile == VatProfile::kHoudini ? frame_view(d.frames, 0) : frame_view(d.rest, 0);
  VatWriter writer(e, info, folder.string(), names, encode_rest_glb(d.asset, d.instances, rest, e.layout, "rig"));
  for (size_t f = 0; f < d.times.size(); ++f) writer.append(frame_view(d.frames, f));
  writer.finish();
  Written w;
  {
    VatDecodeChecker checker(writer);  // the frames were checked as they were appended
    for (size_t f = 0; f + 1 < d.times.size(); ++f) checker.midpoint(f, frame_view(d.midpoints, f));
    w.check = checker.finish();
    w.reference_motion = checker.reference_motion();
    w.decoded_motion = checker.decoded_motion();
  }
  writer.commit(&w.check, {overwrite, nullptr});
  w.encoding = writer.encoding();
  w.names = names;
  return w;
}

class VatWriterTest : public testing::Test {
protected:
  size_t entries() const { return size_t(std::distance(fs::directory_iterator(dir_), fs::directory_iterator())); }
  const testing_support::ScratchDir scratch_{"vat"};
  const fs::path dir_ = scratch_.path();
};

const VatFormat kDqskin{VatProfile::kDqskin, TexelType::kFloat32, NormalMode::kSeparate};

// dqskin float: vertex v of frame f at (v % W, f·R + v / W), w = 1 for positions and 0 for normals, the
// frames' floats bit for bit, zeros everywhere else.
void expect_dqskin_texels(const Image& positions, const Image& normals, const DeformedBatch& batch, size_t w) {
  size_t vertices = 0;
  for (const DeformedBatch::Primitive& p : batch.primitives) vertices += p.vertices;
  const size_t rows = (vertices + w - 1) / w;
  ASSERT_EQ(size_t(positions.spec.width), w);
  ASSERT_EQ(size_t(positions.spec.height), batch.frame_count * rows);
  ASSERT_EQ(positions.spec.nchannels, 4);
  ASSERT_EQ(normals.spec.nchannels, 4);
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
    for (; v < w * rows; ++v)
      for (size_t c = 0; c < 4; ++c) {
        ASSERT_TRUE(same_bits(positions.texel(v % w, f * rows + v / w)[c], 0.0f)) << "padding texel " << v;
        ASSERT_TRUE(same_bits(normals.texel(v % w, f * rows + v / w)[c], 0.0f)) << "padding texel " << v;
      }
  }
}

TEST_F(VatWriterTest, DqskinFloatTexelsAreTheFramesBitForBit) {
  const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf", 0, grid(9, 8));
  const Written w = write_clip(d, kDqskin, dir_);
  const Image positions = read_image(dir_ / "vat_positions.exr");
  const Image normals = read_image(dir_ / "vat_normals.exr");
  EXPECT_EQ(positions.spec.format, OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(positions.spec.channelnames, (std::vector<std::string>{"R", "G", "B", "A"}));
  EXPECT_EQ(positions.spec.get_string_attribute("compression"), "zip");
  EXPECT_EQ(positions.spec.get_string_attribute("DateTime"), "") << "no time stamp";
  EXPECT_EQ(positions.spec.width, 216) << "both instances' vertices in one row";
  expect_dqskin_texels(positions, normals, d.frames, 216);
  EXPECT_EQ(w.check.max_error, 0.0) << "float positions decode exactly";
  EXPECT_EQ(entries(), 4u) << "positions, normals, rest mesh, vat.json; no temporaries left behind";
}

TEST_F(VatWriterTest, DqskinWrapsLongRowsAndPadsWithZeros) {
  // 216 vertices in rows of 10: 22 rows per frame, the last with 6 vertices and 4 zero texels; the
  // second instance's vertices start mid-row.
  const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf", 0, grid(5, 4));
  VatLayout l = plan_vat_layout(kDqskin, 216, 5, 0, false, "test");
  l.wrap = l.width = l.used_width = 10;
  l.wraps = 22;
  l.height = l.used_height = 5 * 22;
  const Written w = write_clip(d, kDqskin, dir_, 0, false, &l);
  expect_dqskin_texels(read_image(dir_ / "vat_positions.exr"), read_image(dir_ / "vat_normals.exr"), d.frames, 10);
  const json side = read_json(dir_ / "vat.json");
  EXPECT_EQ(side["wrap_width"], 10);
  EXPECT_EQ(side["rows_per_frame"], 22);
  EXPECT_EQ(side["height"], 110);
  EXPECT_EQ(w.check.max_error, 0.0);
}

TEST_F(VatWriterTest, LayoutWrapsAtTheDefaultWidthAndHonoursMaxSize) {
  const VatLayout wide = plan_vat_layout(kDqskin, 34159, 1047, 0, false, "t");
  EXPECT_EQ(wide.wrap, 8192u);
  EXPECT_EQ(wide.wraps, 5u);
  EXPECT_EQ(wide.height, 1047u * 5);
  const VatLayout limited = plan_vat_layout(kDqskin, 5000, 3, 4096, true, "t");
  EXPECT_EQ(limited.wrap, 4096u);
  EXPECT_EQ(limited.width, 4096u);
  EXPECT_EQ(limited.used_height, 6u);
  EXPECT_EQ(limited.height, 8u) << "padded to a power of two";
  // Higher than the limit: dqskin splits the frames over pages, the other profiles' runtimes cannot.
  const VatLayout paged = plan_vat_layout(kDqskin, 34159, 1047, 4096, false, "t");
  EXPECT_EQ(paged.wraps, 9u);
  EXPECT_EQ(paged.frames_per_page, 4096u / 9);
  EXPECT_EQ(paged.pages, 3u);
  EXPECT_EQ(paged.page_height(0), 455u * 9);
  EXPECT_EQ(paged.page_height(2), (1047u - 2 * 455) * 9);
  const TexelAt at = paged.position(4100, 500);
  EXPECT_EQ(at.page, 1u);
  EXPECT_EQ(at.x, 4u);
  EXPECT_EQ(at.y, (500u - 455) * 9 + 1);
  try {
    plan_vat_layout({VatProfile::kHoudini, TexelType::kFloat32, NormalMode::kSeparate}, 34159, 1047, 4096, false,
                    "clip 0");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "clip 0: 34159 vertices × 1047 frames do not fit an image 4096 texels high (at most 455 frames do); "
              "lower --fps, or use the dqskin profile, which splits frames over pages; it needs 6282 × 6282 "
              "texels: --max-size 6282 would fit");
  }
  EXPECT_THROW(plan_vat_layout(kDqskin, 5000, 3, 2, false, "t"), InputError) << "one frame is taller than the limit";
}

TEST_F(VatWriterTest, PagesRoundTripAndNameTheirFiles) {
  // 216 vertices in rows of 64 (4 rows a frame) within 16 texels high: 4 frames a page, 13 frames in 4
  // pages, the last with one frame.
  const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf", 0, grid(13, 8));
  VatLayout l = plan_vat_layout(kDqskin, 216, 13, 16, false, "t");  // rows of 16: 14 rows a frame
  ASSERT_EQ(l.wraps, 14u);
  l.wrap = l.width = l.used_width = 64;
  l.wraps = 4;
  l.frames_per_page = 4;
  l.pages = 4;
  l.used_height = l.height = 16;
  const Written w = write_clip(d, kDqskin, dir_, 0, false, &l);
  EXPECT_EQ(w.check.max_error, 0.0);
  EXPECT_GT(w.decoded_motion, 0.0);
  for (size_t p = 0; p < 4; ++p) {
    const Image image = read_image(dir_ / ("vat_positions_page" + std::to_string(p) + ".exr"));
    EXPECT_EQ(image.spec.height, p < 3 ? 16 : 4);
    ASSERT_TRUE(fs::exists(dir_ / ("vat_normals_page" + std::to_string(p) + ".exr")));
    // Frame 4p's vertex 70 at (70 % 64, 70 / 64) of page p.
    const FrameView frame = frame_view(d.frames, 4 * p);
    const PrimitiveView& second = frame.primitives[0].vertices > 70 ? frame.primitives[0] : frame.primitives[1];
    const size_t k = frame.primitives[0].vertices > 70 ? 70 : 70 - frame.primitives[0].vertices;
    EXPECT_TRUE(same_bits(image.texel(6, 1)[0], second.positions[3 * k]));
  }
  EXPECT_FALSE(fs::exists(dir_ / "vat_positions.exr"));
  const json side = read_json(dir_ / "vat.json");
  EXPECT_EQ(side["pages"], 4);
  EXPECT_EQ(side["frames_per_page"], 4);
  EXPECT_EQ(side["page_table"][3]["first_frame"], 12);
  EXPECT_EQ(side["page_table"][3]["frame_count"], 1);
  EXPECT_EQ(side["page_table"][1]["positions"], "vat_positions_page1.exr");
}

TEST_F(VatWriterTest, OpenVatLayoutIsWrapMajorWithNormalsInTheLowerHalf) {
  const VatFormat f{VatProfile::kOpenVat, TexelType::kHalf, NormalMode::kPacked};
  const VatLayout single = plan_vat_layout(f, 1728, 103, 0, false, "t");
  EXPECT_EQ(single.width, 1728u);
  EXPECT_EQ(single.height, 206u);
  EXPECT_EQ(single.packed_normal(5, 7).y, 103u + 7);
  // Over the size limit: OpenVAT's power-of-two wrap, smallest area within a 2:1 ratio.
  const VatLayout wrapped = plan_vat_layout(f, 34159, 100, 4096, false, "t");
  EXPECT_EQ(wrapped.width % 64, 0u);
  EXPECT_TRUE(std::has_single_bit(wrapped.width) && std::has_single_bit(wrapped.height));
  EXPECT_LE(std::max(wrapped.width, wrapped.height), 4096u);
  EXPECT_GE(wrapped.height, 2 * 100 * wrapped.wraps);
  // Vertex v of frame f: column v % W, row (v / W)·F + f; its normal height / 2 lower.
  const TexelAt at = wrapped.position(wrapped.wrap + 3, 9);
  EXPECT_EQ(at.x, 3u);
  EXPECT_EQ(at.y, 100u + 9);
  EXPECT_EQ(wrapped.packed_normal(wrapped.wrap + 3, 9).y, wrapped.height / 2 + 109);
  const glm::dvec2 uv = wrapped.lookup_uv(wrapped.wrap + 3);
  EXPECT_EQ(uv.x, 3.5 / double(wrapped.width));
  EXPECT_EQ(uv.y, 100.5 / double(wrapped.height));
}

TEST_F(VatWriterTest, HandMadeFramesLandWhereTheyBelong) {
  // Two primitives (3 vertices with normals, 2 without) in rows of 2: three rows per frame, texel (1, 2)
  // is padding. Values are chosen so that every texel says where it came from.
  Deformed d;
  d.frames.frame_count = 2;
  d.frames.primitives.resize(2);
  d.frames.primitives[0].vertices = 3;
  d.frames.primitives[1].vertices = 2;
  for (size_t f = 0; f < 2; ++f)
    for (size_t i = 0; i < 2; ++i) {
      DeformedBatch::Primitive& p = d.frames.primitives[i];
      for (size_t v = 0; v < p.vertices; ++v)
        for (size_t c = 0; c < 3; ++c) {
          p.positions.push_back(float(100 * f + 10 * i + v) + 0.25f * float(c));
          if (i == 0) p.normals.push_back(-float(100 * f + v) - 0.5f * float(c));
        }
    }
  VatEncoding e;
  e.layout = plan_vat_layout(kDqskin, 5, 2, 0, false, "t");
  e.layout.wrap = e.layout.width = e.layout.used_width = 2;
  e.layout.wraps = 3;
  e.layout.height = e.layout.used_height = 6;
  VatClipInfo info;
  info.clip = "hand";
  info.times = {0.0, 0.75};
  info.sources = {{0, 0, 0, 3, "a", "m", {}}, {1, 1, 0, 2, "b", "n", {}}};
  VatMeasure measure(e);
  measure.add(frame_view(d.frames, 0), 0, 2);
  measure.add(frame_view(d.frames, 1), 1, 2);
  measure.finish(info, "t");
  VatFileNames names = vat_file_names(kDqskin, "x");
  names.rest_mesh.clear();
  {
    VatWriter writer(e, info, dir_.string(), names, "");
    writer.append(frame_view(d.frames, 0));
    writer.append(frame_view(d.frames, 1));
    writer.finish();
    writer.commit(nullptr, {Overwrite::kReplace, nullptr});
  }
  const Image p = read_image(dir_ / "vat_positions.exr");
  const Image n = read_image(dir_ / "vat_normals.exr");
  ASSERT_EQ(p.spec.width, 2);
  ASSERT_EQ(p.spec.height, 6);
  // Frame 1, primitive 1, vertex 0 is vertex 3 of the frame: texel (1, 1·3 + 1).
  EXPECT_EQ(std::vector<float>(p.texel(1, 4), p.texel(1, 4) + 4), (std::vector<float>{110, 110.25f, 110.5f, 1}));
  EXPECT_EQ(std::vector<float>(n.texel(1, 4), n.texel(1, 4) + 4), (std::vector<float>{0, 0, 0, 0}));
  // Frame 0, vertex 2 (primitive 0): texel (0, 1), its normal too.
  EXPECT_EQ(std::vector<float>(p.texel(0, 1), p.texel(0, 1) + 4), (std::vector<float>{2, 2.25f, 2.5f, 1}));
  EXPECT_EQ(std::vector<float>(n.texel(0, 1), n.texel(0, 1) + 4), (std::vector<float>{-2, -2.5f, -3, 0}));
  expect_dqskin_texels(p, n, d.frames, 2);

  const json side = read_json(dir_ / "vat.json");
  EXPECT_TRUE(side["fps"].is_null()) << "times that are not a grid have no fps";
  EXPECT_EQ(side["frame_times"], json::parse("[0.0, 0.75]"));
  EXPECT_EQ(side["bounds"]["min"], json::parse("[0.0, 0.25, 0.5]"));
  EXPECT_EQ(side["bounds"]["max"], json::parse("[111.0, 111.25, 111.5]"));
  EXPECT_EQ(side["frame_bounds"][1]["min"], json::parse("[100.0, 100.25, 100.5]"));
  EXPECT_EQ(side["frame_bounds"][0]["max"], json::parse("[11.0, 11.25, 11.5]"));
  EXPECT_EQ(side["sources"][1]["first_vertex"], 3);
  EXPECT_FALSE(side["clips"][0]["loop"]);
}

TEST_F(VatWriterTest, DqskinSideFileDescribesTheTextures) {
  const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf", 0, grid(4, 3));
  write_clip(d, kDqskin, dir_, 0, false, nullptr, Overwrite::kReplace, 3);
  const json side = read_json(dir_ / "vat.json");
  EXPECT_EQ(side["format"], "dqskin vertex-animation texture");
  EXPECT_EQ(side["profile"], "dqskin");
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
  EXPECT_EQ(side["pages"], 1);
  EXPECT_EQ(side["attributes"]["positions"]["file"], "vat_positions.exr");
  EXPECT_EQ(side["attributes"]["normals"]["file"], "vat_normals.exr");
  EXPECT_EQ(side["files"]["rest_mesh"], "rest.glb");
  EXPECT_EQ(side["clips"][0]["first_row"], 0);
  EXPECT_EQ(side["clips"][0]["row_count"], 4);
  EXPECT_EQ(side["clips"][0]["duration"].get<double>(), d.times.back());
  ASSERT_EQ(side["frame_bounds"].size(), 4u);
  EXPECT_TRUE(side["remap"].is_null()) << "float positions are not remapped";
  EXPECT_TRUE(side.contains("decode_check"));

  // The bounding box is over every vertex of every frame, exactly (the floats in the texture); each
  // frame's box lies inside it.
  float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (const DeformedBatch::Primitive& p : d.frames.primitives)
    for (size_t i = 0; i < p.positions.size(); ++i) {
      lo[i % 3] = std::min(lo[i % 3], p.positions[i]);
      hi[i % 3] = std::max(hi[i % 3], p.positions[i]);
    }
  for (size_t c = 0; c < 3; ++c) {
    EXPECT_EQ(side["bounds"]["min"][c].get<float>(), lo[c]);
    EXPECT_EQ(side["bounds"]["max"][c].get<float>(), hi[c]);
    for (const json& b : side["frame_bounds"]) {
      EXPECT_GE(b["min"][c].get<float>(), lo[c]);
      EXPECT_LE(b["max"][c].get<float>(), hi[c]);
    }
  }
  const std::vector<VatSource> sources = vat_sources(d.asset, d.instances);
  ASSERT_EQ(side["sources"].size(), 2u);
  size_t first = 0;
  for (size_t i = 0; i < sources.size(); ++i) {
    const json& s = side["sources"][i];
    EXPECT_EQ(s["node"], d.instances[i].node);
    EXPECT_EQ(s["mesh_name"], d.asset.meshes[size_t(d.instances[i].mesh)].name);
    EXPECT_EQ(s["first_vertex"], first);
    EXPECT_EQ(s["vertex_count"], 108);
    first += 108;
  }
}

TEST_F(VatWriterTest, OutputsAreByteIdenticalWhateverTheThreadCount) {
  const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf", 0, grid(12, 11));
  int threads = 0;
  OIIO::getattribute("exr_threads", threads);
  for (const VatFormat& f : {kDqskin, VatFormat{VatProfile::kOpenVat, TexelType::kUnorm16, NormalMode::kSeparate},
                             VatFormat{VatProfile::kHoudini, TexelType::kHalf, NormalMode::kPacked}}) {
    const fs::path a = dir_ / to_string(f.profile) / "a", b = dir_ / to_string(f.profile) / "b",
                   c = dir_ / to_string(f.profile) / "c";
    for (const fs::path& p : {a, b, c}) fs::create_directories(p);
    OIIO::attribute("exr_threads", 1);
    const Written w = write_clip(d, f, a);
    OIIO::attribute("exr_threads", 8);
    write_clip(d, f, b);
    OIIO::attribute("exr_threads", threads);
    sleep(1);  // a time stamp would now differ
    write_clip(d, f, c);
    for (const std::string& name : {w.names.positions, w.names.normals, w.names.rest_mesh, w.names.dqskin_side_file,
                                    w.names.profile_side_file}) {
      if (name.empty()) continue;
      const std::string bytes = read_file(a / name);
      EXPECT_FALSE(bytes.empty()) << name;
      EXPECT_EQ(bytes, read_file(b / name)) << name;
      EXPECT_EQ(bytes, read_file(c / name)) << name;
    }
  }
}

// An image of `rows` rows written through TexelFileWriter in bands of `band_rows` rows (the rows after
// `skip` zeros), with OpenEXR's pool at `threads`; the file's bytes.
std::string write_texels(const fs::path& path, TexelType type, size_t width, size_t rows, int channels,
                         const std::string& compression, size_t band_rows, size_t skip, int threads) {
  int saved = 0;
  OIIO::getattribute("exr_threads", saved);
  OIIO::attribute("exr_threads", threads);
  {
    AtomicFile file(path.string(), false);
    TexelFileWriter writer(file, type, width, rows, channels, compression, true);
    for (size_t first = skip; first < rows; first += band_rows) {
      TexelImage band(type, width, std::min(band_rows, rows - first), channels, first);
      for (size_t y = first; y < first + band.rows(); ++y)
        for (size_t x = 0; x < width; ++x)
          for (int c = 0; c < channels; ++c)  // smooth, as positions are, with some noise in the low bits
          {
            const float v = float(std::sin(double(x) * 0.01 + double(y) * 0.002 + c)) + float((x * 31 + y) % 7) * 1e-4f;
            float h = v;
            if (type == TexelType::kHalf) {
              EXPECT_TRUE(to_half(v, h));
            }
            band.set(x, y, c, h);
          }
      writer.write(band);
    }
    writer.close();
    file.commit({});
  }
  OIIO::attribute("exr_threads", saved);
  return read_file(path);
}

TEST_F(VatWriterTest, GatheredChunksOnEveryThreadWriteTheBytesOfOneThreadRowByRow) {
  // 300 wide RGBA float rows are 4.7 KB: 2,500 rows are 12 MB, more than one chunk (8 MiB), with a last
  // chunk that is not a whole number of blocks. One row at a time on one thread is how the bytes were
  // made before rows were gathered; a frame's 5 rows at a time on 8 threads and one band of everything
  // must give the same file, and every band size the same digest.
  for (const std::string compression : {"zip", "piz", "rle", "zips", "none"})
    for (const TexelType type : {TexelType::kFloat32, TexelType::kHalf}) {
      const std::string what = compression + " " + to_string(type);
      const std::string one = write_texels(dir_ / "one.exr", type, 300, 2500, 4, compression, 1, 0, 1);
      EXPECT_GT(one.size(), 10000u) << what;
      EXPECT_EQ(one, write_texels(dir_ / "five.exr", type, 300, 2500, 4, compression, 5, 0, 8)) << what;
      EXPECT_EQ(one, write_texels(dir_ / "all.exr", type, 300, 2500, 4, compression, 2500, 0, 0)) << what;
      EXPECT_NE(one, write_texels(dir_ / "skip.exr", type, 300, 2500, 4, compression, 5, 40, 8))
          << what << ": 40 rows of zeros differ";
    }
}

TEST_F(VatWriterTest, DigestIsOfTheBytesHowEverTheyAreCut) {
  std::vector<uint8_t> bytes(1000);
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = uint8_t(i * 37 + i / 7);
  TexelDigest whole, pieces;
  whole.add(bytes.data(), bytes.size());
  for (size_t at = 0, step = 1; at < bytes.size(); at += step, step = step % 45 + 3)
    pieces.add(bytes.data() + at, std::min(step, bytes.size() - at));
  EXPECT_EQ(whole.value(), pieces.value());
  bytes[500] ^= 1;
  TexelDigest changed;
  changed.add(bytes.data(), bytes.size());
  EXPECT_NE(whole.value(), changed.value());
  TexelDigest longer;
  longer.add(bytes.data(), bytes.size() - 1);
  EXPECT_NE(changed.value(), longer.value());
}

// A clip written with its frames checked in memory, and its positions' temporary replaced by `tamper` before
// the read-back: the check must fail naming the file.
void expect_read_back_fails(const Deformed& d, const VatFormat& format, const fs::path& folder,
                            const std::function<void(const std::string& temporary, const VatEncoding&)>& tamper,
                            const std::string& why = "") {
  fs::create_directories(folder);
  VatEncoding e;
  e.layout = plan_vat_layout(format, vertex_count(d), d.times.size(), 0, false, "t");
  if (format.profile == VatProfile::kOpenVat) e.rest = all_positions(frame_view(d.rest, 0));
  VatMeasure measure(e);
  VatClipInfo info;
  info.times = d.times;
  for (size_t f = 0; f < d.times.size(); ++f) measure.add(frame_view(d.frames, f), f, d.times.size());
  measure.finish(info, "t");
  VatWriter writer(e, info, folder.string(), vat_file_names(format, "x"), "");
  for (size_t f = 0; f < d.times.size(); ++f) writer.append(frame_view(d.frames, f));
  writer.finish();
  tamper(writer.positions().temporary, writer.encoding());
  try {
    VatDecodeChecker checker(writer);
    for (size_t f = 0; f + 1 < d.times.size(); ++f) checker.midpoint(f, frame_view(d.midpoints, f));
    checker.finish();
    ADD_FAILURE() << "a tampered file passed the check";
  } catch (const OutputError& err) {
    EXPECT_EQ(std::string(err.what()).rfind(writer.positions().name + ": ", 0), 0u) << err.what();
    EXPECT_NE(std::string(err.what()).find(why), std::string::npos) << err.what();
  }
}

TEST_F(VatWriterTest, AFileChangedAfterWritingFailsTheCheck) {
  // The frames are compared in memory; what proves the file holds those texels is the digest of the
  // rows read back. A file re-encoded with one texel changed decodes cleanly, so only the digest can
  // catch it: in a row the midpoints read (frame 0) and in the last row, which only the final read
  // reaches. A byte flipped in the compressed data fails as unreadable or as different.
  const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/twisted_cylinder.gltf", 0, grid(9, 8));
  auto change_texel = [](size_t x, bool last_row) {
    return [x, last_row](const std::string& temporary, const VatEncoding& e) {
      auto in = OIIO::ImageInput::open(temporary);
      ASSERT_TRUE(in);
      OIIO::ImageSpec spec = in->spec();
      std::vector<float> texels(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
      ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, texels.data()));
      in->close();
      const size_t y = last_row ? size_t(spec.height) - 1 : 0;
      float& v = texels[(y * size_t(spec.width) + x) * size_t(spec.nchannels)];
      v += v < 0.5f ? 0.25f : -0.25f;  // within [0, 1] for the PNG
      const bool png = spec.format == OIIO::TypeDesc::UINT16 || spec.format == OIIO::TypeDesc::UINT8;
      auto out = OIIO::ImageOutput::create(png ? "png" : "openexr");  // the temporary's name has no extension
      ASSERT_TRUE(out && out->open(temporary, spec));
      ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, texels.data()));
      out->close();
      (void)e;
    };
  };
  const std::string differ = "differ from those the check compared";
  expect_read_back_fails(d, kDqskin, dir_ / "first", change_texel(3, false), differ);
  expect_read_back_fails(d, kDqskin, dir_ / "last", change_texel(0, true), differ);
  expect_read_back_fails(d, VatFormat{VatProfile::kOpenVat, TexelType::kUnorm16, NormalMode::kSeparate}, dir_ / "png",
                         change_texel(1, false), differ);
  expect_read_back_fails(d, kDqskin, dir_ / "flipped", [](const std::string& temporary, const VatEncoding&) {
    std::fstream f(temporary, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(0, std::ios::end);
    const std::streamoff size = f.tellg();
    f.seekg(size - 40);
    char c = 0;
    f.get(c);
    f.seekp(size - 40);
    f.put(char(c ^ 0x10));
  });
  // The same clip untampered passes: the failures above are the tampering's.
  fs::create_directories(dir_ / "clean");
  const Written w = write_clip(d, kDqskin, dir_ / "clean");
  EXPECT_EQ(w.check.max_error, 0.0);
}

TEST_F(VatWriterTest, RefuseDifferentKeepsEqualFilesAndChangesNoneWhenOneDiffers) {
  const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf", 0, grid(3, 2));
  write_clip(d, kDqskin, dir_);
  const std::string positions = read_file(dir_ / "vat_positions.exr");
  const std::string json_text = read_file(dir_ / "vat.json");
  write_clip(d, kDqskin, dir_, 0, false, nullptr, Overwrite::kRefuseDifferent);  // equal: no error
  // Same images, another fps: only the JSON differs, and nothing is renamed, the images included.
  fs::remove(dir_ / "vat_normals.exr");
  try {
    write_clip(d, kDqskin, dir_, 0, false, nullptr, Overwrite::kRefuseDifferent, 50);
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()), (dir_ / "vat.json").string() + ": exists with different contents; not overwritten");
  }
  EXPECT_FALSE(fs::exists(dir_ / "vat_normals.exr")) << "refused before any rename";
  EXPECT_EQ(read_file(dir_ / "vat_positions.exr"), positions);
  EXPECT_EQ(read_file(dir_ / "vat.json"), json_text);
  EXPECT_EQ(entries(), 3u);
}

TEST_F(VatWriterTest, UnfinishedWriterLeavesNoFiles) {
  const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf", 0, grid(4, 4));
  {
    VatEncoding e;
    e.layout = plan_vat_layout(kDqskin, vertex_count(d), 4, 0, false, "t");
    VatWriter writer(e, {}, dir_.string(), vat_file_names(kDqskin, "x"), "");
    writer.append(frame_view(d.frames, 0));
    writer.append(frame_view(d.frames, 1));
    EXPECT_THROW(writer.finish(), std::logic_error) << "two frames are missing";
  }
  EXPECT_EQ(entries(), 0u);
}

TEST_F(VatWriterTest, UnwritableFolderIsAnOutputErrorNamingTheFile) {
  const fs::path missing = dir_ / "missing";
  VatEncoding e;
  e.layout = plan_vat_layout(kDqskin, 10, 1, 0, false, "t");
  try {
    VatWriter writer(e, {}, missing.string(), vat_file_names(kDqskin, "x"), "");
    FAIL() << "expected OutputError";
  } catch (const OutputError& err) {
    EXPECT_EQ(std::string(err.what()).rfind((missing / "vat_positions.exr").string() + ": ", 0), 0u) << err.what();
  }
  EXPECT_EQ(entries(), 0u);
}

TEST_F(VatWriterTest, ABakeOfOnePoseInEveryRowDecodesWithoutMotion) {
  // The failure users report: a bake that "succeeded" with the bind pose in every row. The frames fed to
  // the writer were the bind pose too, so the in-memory comparison of frames sees nothing wrong; the
  // midpoints, deformed apart, see the clip move and the texture stand still, the figures the bake fails
  // on.
  const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/twisted_cylinder.gltf", 0, grid(9, 8));
  VatEncoding e;
  e.layout = plan_vat_layout(kDqskin, vertex_count(d), d.times.size(), 0, false, "t");
  VatWriter writer(e, {}, dir_.string(), vat_file_names(kDqskin, "x"), "");
  for (size_t f = 0; f < d.times.size(); ++f) writer.append(frame_view(d.rest, 0));
  writer.finish();
  VatDecodeChecker checker(writer);
  for (size_t f = 0; f + 1 < d.times.size(); ++f) checker.midpoint(f, frame_view(d.midpoints, f));
  const DecodeCheck c = checker.finish();
  EXPECT_EQ(checker.decoded_motion(), 0.0);
  EXPECT_GT(checker.reference_motion(), 0.1) << "the twist moves the cylinder's rim by more than a tenth";
  EXPECT_EQ(c.max_error, 0.0) << "the frames are the ones fed";
  EXPECT_GT(c.max_midpoint_error, 0.1);
}

TEST_F(VatWriterTest, ClipsOfOneTextureHaveTheirOwnFiguresAndMotion) {
  // Two clips in one texture: frames 0-4 the twist, frames 5-8 stuck in frame 5's pose. The second clip's
  // motion is measured from its own first frame: it decodes without motion while its midpoints (deformed
  // apart) move; the first clip moves. The whole figures are the clips' together.
  const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/twisted_cylinder.gltf", 0, grid(9, 8));
  VatEncoding e;
  e.layout = plan_vat_layout(kDqskin, vertex_count(d), d.times.size(), 0, false, "t");
  VatWriter writer(e, {}, dir_.string(), vat_file_names(kDqskin, "x"), "");
  writer.frame_check()->set_clip_starts({0, 5});
  for (size_t f = 0; f < d.times.size(); ++f) writer.append(frame_view(d.frames, std::min<size_t>(f, 5)));
  writer.finish();
  VatDecodeChecker checker(writer);
  for (size_t f = 0; f + 1 < d.times.size(); ++f)
    if (f != 4) checker.midpoint(f, frame_view(d.midpoints, f));  // not across the clips' boundary
  const DecodeCheck whole = checker.finish();
  const DecodeCheck first = checker.clip_result(0), second = checker.clip_result(1);
  EXPECT_GT(checker.decoded_motion(0), 0.1);
  EXPECT_EQ(checker.decoded_motion(1), 0.0);
  EXPECT_GT(checker.reference_motion(1), 0.1);
  EXPECT_EQ(first.max_error, 0.0);
  EXPECT_EQ(second.max_error, 0.0) << "the frames are the ones fed";
  EXPECT_GT(second.max_midpoint_error, first.max_midpoint_error);
  EXPECT_EQ(whole.samples, first.samples + second.samples);
  EXPECT_EQ(whole.samples, (9 + 7) * vertex_count(d));
  EXPECT_EQ(whole.max_midpoint_error, std::max(first.max_midpoint_error, second.max_midpoint_error));
}

TEST_F(VatWriterTest, HalfOverflowIsAnErrorNamingFrameAndVertex) {
  Deformed d;
  d.times = {0.0};
  d.frames.frame_count = 1;
  d.frames.primitives.resize(1);
  d.frames.primitives[0].vertices = 2;
  d.frames.primitives[0].positions = {0, 0, 0, 1, 70000, 2};
  VatEncoding e;
  e.layout = plan_vat_layout({VatProfile::kDqskin, TexelType::kHalf, NormalMode::kNone}, 2, 1, 0, false, "t");
  VatClipInfo info;
  info.asset = "big";
  info.clip = "clip";
  info.times = {0.0};
  VatWriter writer(e, info, dir_.string(), vat_file_names(e.layout.format, "big"), "");
  try {
    writer.append(frame_view(d.frames, 0));
    FAIL() << "expected InputError";
  } catch (const InputError& err) {
    EXPECT_NE(std::string(err.what()).find("clip clip, frame 0, vertex 1: value 70000"), std::string::npos) << err.what();
    EXPECT_NE(std::string(err.what()).find("overflows half"), std::string::npos) << err.what();
  }
}

// The decode-back round trip of one rig clip in one format, within the bounds the encoding allows.
struct RoundTrip {
  VatFormat format;
  double normal_degrees;  // the largest normal angle the encoding may show at the baked frames
};

std::string format_name(const VatFormat& f) {
  std::string name = std::string(to_string(f.profile)) + "_" + to_string(f.type) + "_" + to_string(f.normals);
  for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
}

class VatRoundTrip : public VatWriterTest, public testing::WithParamInterface<RoundTrip> {};

TEST_P(VatRoundTrip, DecodesWithinTheEncodingsBound) {
  const RoundTrip& r = GetParam();
  for (const char* rig : {"twisted_cylinder.gltf", "bending_arm.gltf", "two_skins.gltf", "nonuniform_scale.gltf"}) {
    SCOPED_TRACE(rig);
    const Deformed d = deform_clip(std::string(DQSKIN_TESTDATA_DIR) + "/" + rig, 0, grid(13, 8));
    const fs::path folder = dir_ / rig;
    fs::create_directories(folder);
    const Written w = write_clip(d, r.format, folder);
    // Positions: the encoding's bound (float: the decode's arithmetic only; half: half its ulp; png: half a
    // step of the remapped range); asserted at every vertex of every frame.
    const double bound = position_encoding_bound(w.encoding);
    EXPECT_LE(w.check.max_error, bound);
    EXPECT_LE(w.check.p99_error, w.check.max_error);
    if (r.format.normals != NormalMode::kNone) {
      EXPECT_LE(w.check.max_normal_degrees, r.normal_degrees);
    }
    EXPECT_GT(w.decoded_motion, 0.5 * w.reference_motion) << "the frames decode to the clip's motion";
    EXPECT_EQ(w.check.samples, vertex_count(d) * (2 * d.times.size() - 1));
  }
}

// Bounds for normals, in degrees: float 1e-4 (rounding of unit vectors), half 0.1 (2^-11 per component),
// png16 0.01, png8 0.6 (1/255 of the range [-1, 1] per component: up to about 0.45°), octahedral as measured
// in texel_encoding_test. Houdini's packed code: 50°. It keeps 5 bits of one spheremap coordinate (and the
// decode divides by 1024 where the encoder multiplied by 1023); near the downward pole, the spheremap's
// rim, a coordinate error of 1/31 turns the normal by up to about 45° (measured 47°). That is the format's,
// and docs/formats.md says so.
INSTANTIATE_TEST_SUITE_P(
    Formats, VatRoundTrip,
    testing::Values(RoundTrip{{VatProfile::kDqskin, TexelType::kFloat32, NormalMode::kSeparate}, 1e-4},
                    RoundTrip{{VatProfile::kDqskin, TexelType::kHalf, NormalMode::kSeparate}, 0.1},
                    RoundTrip{{VatProfile::kDqskin, TexelType::kUnorm16, NormalMode::kSeparate}, 0.01},
                    RoundTrip{{VatProfile::kDqskin, TexelType::kUnorm8, NormalMode::kSeparate}, 0.6},
                    RoundTrip{{VatProfile::kDqskin, TexelType::kUnorm16, NormalMode::kOct8}, 1.0},
                    RoundTrip{{VatProfile::kDqskin, TexelType::kHalf, NormalMode::kOct16}, 0.005},
                    RoundTrip{{VatProfile::kDqskin, TexelType::kFloat32, NormalMode::kNone}, 0},
                    RoundTrip{{VatProfile::kOpenVat, TexelType::kFloat32, NormalMode::kPacked}, 1e-4},
                    RoundTrip{{VatProfile::kOpenVat, TexelType::kHalf, NormalMode::kPacked}, 0.1},
                    RoundTrip{{VatProfile::kOpenVat, TexelType::kHalf, NormalMode::kSeparate}, 0.1},
                    RoundTrip{{VatProfile::kOpenVat, TexelType::kUnorm16, NormalMode::kPacked}, 0.01},
                    RoundTrip{{VatProfile::kOpenVat, TexelType::kUnorm8, NormalMode::kSeparate}, 0.6},
                    RoundTrip{{VatProfile::kHoudini, TexelType::kFloat32, NormalMode::kSeparate}, 1e-3},
                    RoundTrip{{VatProfile::kHoudini, TexelType::kHalf, NormalMode::kSeparate}, 0.2},
                    RoundTrip{{VatProfile::kHoudini, TexelType::kFloat32, NormalMode::kPacked}, 50.0},
                    RoundTrip{{VatProfile::kHoudini, TexelType::kHalf, NormalMode::kPacked}, 50.0}),
    [](const testing::TestParamInfo<RoundTrip>& p) { return format_name(p.param.format); });

// The shared sample models: eight frames spread over the first clip of each, in one format of each profile
// family, decoded within the same bounds as the rigs.
class VatSharedRoundTrip : public VatWriterTest, public testing::WithParamInterface<const char*> {};

TEST_P(VatSharedRoundTrip, DecodesWithinTheEncodingsBound) {
  const fs::path path = fs::path(DQSKIN_SHARED_TESTDATA_DIR) / GetParam();
  if (!fs::exists(path)) GTEST_SKIP() << "shared test data not found: " << path;
  const Asset probe = load_asset(path.string());
  std::vector<double> times = {0.0};
  if (!probe.clips.empty()) {
    const std::vector<double> all = frame_times(probe.clips[0], FrameSpec{});
    times.clear();
    for (size_t i = 0; i < 8; ++i) times.push_back(all[i * (all.size() - 1) / 7]);
  }
  const Deformed d = deform_clip(path.string(), 0, times);
  const std::pair<VatFormat, double> formats[] = {
      {{VatProfile::kDqskin, TexelType::kFloat32, NormalMode::kSeparate}, 1e-4},
      {{VatProfile::kDqskin, TexelType::kUnorm16, NormalMode::kOct16}, 0.005},
      {{VatProfile::kOpenVat, TexelType::kHalf, NormalMode::kPacked}, 0.1},
      {{VatProfile::kOpenVat, TexelType::kUnorm8, NormalMode::kSeparate}, 0.6},
      {{VatProfile::kHoudini, TexelType::kHalf, NormalMode::kSeparate}, 0.2}};
  for (const auto& [format, degrees] : formats) {
    SCOPED_TRACE(format_name(format));
    const fs::path folder = dir_ / format_name(format);
    fs::create_directories(folder);
    // Images of 2048 texels a side at most, so that the larger models wrap.
    const Written w = write_clip(d, format, folder, 2048);
    EXPECT_LE(w.check.max_error, position_encoding_bound(w.encoding));
    EXPECT_LE(w.check.max_normal_degrees, degrees);
    // A clip that moves by more than the encoding can resolve decodes to that motion (greenman's first
    // clip moves by float noise only: 1e-5).
    if (w.reference_motion > 4 * position_encoding_bound(w.encoding)) {
      EXPECT_GT(w.decoded_motion, 0.5 * w.reference_motion);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Models, VatSharedRoundTrip,
                         testing::Values("CesiumMan/CesiumMan.glb", "Fox/Fox.glb", "RiggedFigure/RiggedFigure.glb",
                                         "RiggedSimple/RiggedSimple.glb", "BrainStem/BrainStem.glb",
                                         "raylib_robot/robot.glb", "raylib_greenman/greenman.glb",
                                         "RecursiveSkeletons/RecursiveSkeletons.glb", "SimpleSkin/SimpleSkin.gltf",
                                         "AnimatedMorphCube/AnimatedMorphCube.glb", "InterpolationTest/InterpolationTest.glb"),
                         testing_support::model_test_name);

// The rest mesh of every rig and shared model, for the dqskin and openvat layouts: read back with dqskin's
// own loader, its positions are the rest frame's and each vertex's TEXCOORD_1 leads back to its texel;
// the source's TEXCOORD_0 is kept. With DQSKIN_REST_GLB_SAMPLE_DIR set the files are also written there,
// for the Khronos glTF-Validator (CTest's rest_glb_validator).
class RestGlb : public VatWriterTest, public testing::WithParamInterface<const char*> {};

TEST_P(RestGlb, LookupLeadsEachVertexToItsTexel) {
  const std::string param = GetParam();
  const fs::path path = testing_support::model_path(param);
  if (!fs::exists(path)) GTEST_SKIP() << "shared test data not found: " << path;
  const Deformed d = deform_clip(path.string(), 0, {0.0});
  const char* sample_dir = std::getenv("DQSKIN_REST_GLB_SAMPLE_DIR");
  for (const VatFormat& f : {kDqskin, VatFormat{VatProfile::kOpenVat, TexelType::kHalf, NormalMode::kPacked}}) {
    SCOPED_TRACE(to_string(f.profile));
    // A narrow wrap, so that lookups span several rows.
    const VatLayout l = plan_vat_layout(f, vertex_count(d), 3, 1024, false, "t");
    const std::string bytes = encode_rest_glb(d.asset, d.instances, frame_view(d.rest, 0), l, "rest");
    const fs::path file = dir_ / (std::string(to_string(f.profile)) + ".glb");
    std::ofstream(file, std::ios::binary) << bytes;
    if (sample_dir && *sample_dir) {
      fs::create_directories(sample_dir);
      std::string name = fs::path(param).stem().string() + "_" + to_string(f.profile) + ".glb";
      std::ofstream(fs::path(sample_dir) / name, std::ios::binary) << bytes;
    }
    const Asset back = load_asset(file.string());
    ASSERT_EQ(back.meshes.size(), 1u);
    size_t v = 0, source = 0;
    for (const MeshInstance& inst : d.instances)
      for (const Primitive& src : d.asset.meshes[size_t(inst.mesh)].primitives) {
        const Primitive& p = back.meshes[0].primitives.at(source);
        const DeformedBatch::Primitive& rest = d.rest.primitives[source++];
        ASSERT_EQ(p.vertex_count(), src.vertex_count());
        ASSERT_EQ(p.uv1.size(), p.vertex_count());
        if (!src.uv0.empty()) {
          EXPECT_EQ(p.uv0, src.uv0);
        }
        for (size_t k = 0; k < p.vertex_count(); ++k, ++v) {
          for (int c = 0; c < 3; ++c) ASSERT_EQ(p.positions[k][c], rest.positions[3 * k + size_t(c)]);
          const TexelAt at = l.position(v, 0);
          const glm::vec2 uv = p.uv1[k];
          if (f.profile == VatProfile::kDqskin) {
            ASSERT_EQ(uv, glm::vec2(float(at.x), float(at.y))) << "vertex " << v;
          } else {  // the texel centre: back to the texel by floor(uv · size)
            ASSERT_EQ(size_t(std::floor(double(uv.x) * double(l.width))), at.x) << "vertex " << v;
            ASSERT_EQ(size_t(std::floor(double(uv.y) * double(l.height))), at.y) << "vertex " << v;
          }
        }
      }
    EXPECT_EQ(v, vertex_count(d));
  }
}

INSTANTIATE_TEST_SUITE_P(Models, RestGlb,
                         testing::Values("twisted_cylinder.gltf", "two_skins.gltf", "textured_cylinder.gltf",
                                         "morph_skin.gltf", "CesiumMan/CesiumMan.glb", "Fox/Fox.glb",
                                         "BrainStem/BrainStem.glb", "RiggedFigure/RiggedFigure.glb",
                                         "raylib_robot/robot.glb", "AnimatedMorphCube/AnimatedMorphCube.glb"),
                         testing_support::model_test_name);

}  // namespace
}  // namespace dqskin::texture
