// Compressed glTF inputs (EXT_meshopt_compression, KHR_draco_mesh_compression): each test compresses an
// uncompressed rig of testdata/ with the codec's own encoder, as an optimizer would, and checks that
// loading the result gives the Asset the uncompressed file gives.
#include "dqskin/error.hpp"
#include "dqskin/load.hpp"
#include "../asset/source_document.hpp"
#include "../base/base64.hpp"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>

#include <unistd.h>

#include "../test_support/glb_output_check.hpp"

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Bytes = std::vector<uint8_t>;

const fs::path kTestdata = DQSKIN_TESTDATA_DIR;

// ---------------------------------------------------------------------------------------------------
// An uncompressed rig as JSON and its one buffer, and the ways to write it back.

struct Rig {
  json doc;
  Bytes bin;  // buffer 0
};

Rig read_rig(const std::string& name) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  const fs::path path = kTestdata / name;
  if (!loader.LoadASCIIFromFile(&model, &err, &warn, path.string())) throw std::runtime_error(err);
  if (model.buffers.size() != 1) throw std::runtime_error(name + ": expected one buffer");
  std::ifstream in(path);
  Rig rig{json::parse(in), model.buffers[0].data};
  rig.doc["buffers"][0].erase("uri");
  return rig;
}

void pad4(Bytes& b, uint8_t fill = 0) {
  while (b.size() % 4) b.push_back(fill);
}

void put32(Bytes& out, size_t v) {
  for (int s = 0; s < 32; s += 8) out.push_back(uint8_t(v >> s));
}

// A .glb of `doc` whose BIN chunk is `bin` (buffer 0 must have no uri).
Bytes glb(const json& doc, Bytes bin) {
  std::string text = doc.dump();
  while (text.size() % 4) text += ' ';
  pad4(bin);
  Bytes out = {'g', 'l', 'T', 'F'};
  put32(out, 2);
  put32(out, 12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size()));
  put32(out, text.size());
  out.insert(out.end(), {'J', 'S', 'O', 'N'});
  out.insert(out.end(), text.begin(), text.end());
  if (!bin.empty()) {
    put32(out, bin.size());
    out.insert(out.end(), {'B', 'I', 'N', 0});
    out.insert(out.end(), bin.begin(), bin.end());
  }
  return out;
}

using io::base64;

Asset load_bytes(const Bytes& bytes, const LoadOptions& options = {}) {
  return load_asset_from_memory(bytes, "compressed", ".", options);
}

Asset load_rig(const Rig& rig) { return load_bytes(glb(rig.doc, rig.bin)); }

std::string load_error(const Bytes& bytes, const LoadOptions& options = {}) {
  try {
    load_bytes(bytes, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(loaded)";
}

void add_extension(json& doc, const std::string& name, bool required) {
  auto add = [&](const char* key) {
    if (!doc.contains(key)) doc[key] = json::array();
    if (std::find(doc[key].begin(), doc[key].end(), name) == doc[key].end()) doc[key].push_back(name);
  };
  add("extensionsUsed");
  if (required) add("extensionsRequired");
}

// ---------------------------------------------------------------------------------------------------
// Comparing assets: everything the loader decodes from accessors, exactly or within a tolerance per
// kind of data.

struct Tolerance {
  float positions = 0, normals = 0, tangents = 0, uv = 0, colors = 0, weights = 0, targets = 0, keys = 0;
  bool rotations_up_to_sign = false;  // quaternion filter: q and -q are the same rotation
  // meshopt's TRIANGLES codec may start a triangle at another corner (same winding): the same triangles.
  bool triangles_up_to_rotation = false;
};

// Each triangle of a list turned to start at its smallest index (winding kept).
std::vector<uint32_t> canonical_triangles(std::vector<uint32_t> list) {
  for (size_t t = 0; t + 2 < list.size(); t += 3)
    while (list[t] > list[t + 1] || list[t] > list[t + 2]) std::rotate(&list[t], &list[t + 1], &list[t + 3]);
  return list;
}

template <typename V>
void expect_near(const std::vector<V>& a, const std::vector<V>& b, float tolerance, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  float worst = 0;
  size_t at = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const float d = glm::length(glm::vec<V::length(), float>(a[i]) - glm::vec<V::length(), float>(b[i]));
    if (!(d <= worst)) worst = d, at = i;
  }
  EXPECT_LE(worst, tolerance) << what << ": element " << at;
}

void expect_same_asset(const Asset& want, const Asset& got, const Tolerance& t = {}) {
  ASSERT_EQ(want.meshes.size(), got.meshes.size());
  for (size_t m = 0; m < want.meshes.size(); ++m) {
    ASSERT_EQ(want.meshes[m].primitives.size(), got.meshes[m].primitives.size());
    EXPECT_EQ(want.meshes[m].weights, got.meshes[m].weights);
    for (size_t p = 0; p < want.meshes[m].primitives.size(); ++p) {
      const Primitive& a = want.meshes[m].primitives[p];
      const Primitive& b = got.meshes[m].primitives[p];
      const std::string what = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
      EXPECT_EQ(a.mode, b.mode) << what;
      EXPECT_EQ(a.material, b.material) << what;
      expect_near(a.positions, b.positions, t.positions, what + " POSITION");
      expect_near(a.normals, b.normals, a.normals_generated ? std::max(t.positions * 100, 1e-5f) : t.normals, what + " NORMAL");
      EXPECT_EQ(a.normals_generated, b.normals_generated) << what;
      expect_near(a.tangents, b.tangents, t.tangents, what + " TANGENT");
      expect_near(a.uv0, b.uv0, t.uv, what + " TEXCOORD_0");
      expect_near(a.uv1, b.uv1, t.uv, what + " TEXCOORD_1");
      expect_near(a.colors, b.colors, t.colors, what + " COLOR_0");
      if (t.triangles_up_to_rotation && a.mode == PrimitiveMode::kTriangles)
        EXPECT_EQ(canonical_triangles(a.indices), canonical_triangles(b.indices)) << what;
      else
        EXPECT_EQ(a.indices, b.indices) << what;
      EXPECT_EQ(a.influences, b.influences) << what;
      EXPECT_EQ(a.joints, b.joints) << what;
      ASSERT_EQ(a.weights.size(), b.weights.size()) << what;
      for (size_t i = 0; i < a.weights.size(); ++i) ASSERT_NEAR(a.weights[i], b.weights[i], t.weights) << what << " weight " << i;
      ASSERT_EQ(a.targets.size(), b.targets.size()) << what;
      for (size_t k = 0; k < a.targets.size(); ++k) {
        expect_near(a.targets[k].positions, b.targets[k].positions, t.targets, what + " target POSITION");
        expect_near(a.targets[k].normals, b.targets[k].normals, t.targets, what + " target NORMAL");
      }
    }
  }
  ASSERT_EQ(want.skins.size(), got.skins.size());
  for (size_t s = 0; s < want.skins.size(); ++s) {
    EXPECT_EQ(want.skins[s].joints, got.skins[s].joints);
    EXPECT_EQ(want.skins[s].inverse_bind, got.skins[s].inverse_bind);
  }
  ASSERT_EQ(want.clips.size(), got.clips.size());
  for (size_t c = 0; c < want.clips.size(); ++c) {
    ASSERT_EQ(want.clips[c].channels.size(), got.clips[c].channels.size());
    for (size_t k = 0; k < want.clips[c].channels.size(); ++k) {
      const Channel& a = want.clips[c].channels[k];
      const Channel& b = got.clips[c].channels[k];
      EXPECT_EQ(a.times, b.times);
      ASSERT_EQ(a.values.size(), b.values.size());
      const bool rotation = a.path == TargetPath::kRotation;
      for (size_t i = 0; i < a.values.size(); i += size_t(a.components)) {
        float sign = 1;
        if (rotation && t.rotations_up_to_sign) {
          float dot = 0;
          for (int j = 0; j < 4; ++j) dot += a.values[i + size_t(j)] * b.values[i + size_t(j)];
          sign = dot < 0 ? -1.0f : 1.0f;
        }
        for (size_t j = 0; j < size_t(a.components); ++j)
          ASSERT_NEAR(a.values[i + j], sign * b.values[i + j], t.keys) << "clip " << c << " channel " << k << " value " << i + j;
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------------
// EXT_meshopt_compression, as gltfpack writes it: the compressed views in buffer 0 (the BIN chunk), the
// uncompressed layout in a fallback buffer 1 without data.

enum class IndexMode { kTriangles, kIndices };

struct MeshoptOptions {
  IndexMode index_mode = IndexMode::kTriangles;
  bool required = true;
  bool fallback_flag = true;   // extensions.EXT_meshopt_compression.fallback on buffer 1
  bool fallback_data = false;  // buffer 1 has a uri (a data URI of `fallback_fill` bytes) instead of none
  uint8_t fallback_fill = 0;
  std::set<size_t> filtered;   // views that are already filtered (filter name in `filters`): ATTRIBUTES
  std::map<size_t, std::string> filters;
};

// The views that hold indices of triangle lists, and every view an accessor of `doc` uses, with its
// element size.
struct ViewUse {
  bool triangle_indices = false;
  bool indices = false;
  size_t element = 0;
};

size_t component_size(int type) { return type == 5120 || type == 5121 ? 1 : type == 5122 || type == 5123 ? 2 : 4; }
size_t components(const std::string& type) {
  return type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : type == "VEC4" || type == "MAT2" ? 4 : type == "MAT3" ? 9 : 16;
}

std::map<size_t, ViewUse> view_uses(const json& doc) {
  std::map<size_t, ViewUse> uses;
  for (const json& a : doc["accessors"])
    if (a.contains("bufferView"))
      uses[a["bufferView"]].element = component_size(a["componentType"]) * components(a["type"]);
  for (const json& mesh : doc["meshes"])
    for (const json& p : mesh["primitives"])
      if (p.contains("indices")) {
        const json& a = doc["accessors"][size_t(p["indices"])];
        ViewUse& u = uses[a["bufferView"]];
        u.indices = true;
        u.triangle_indices = p.value("mode", 4) == 4;
      }
  return uses;
}

// The rig with every view compressed that the extension can hold: index views as TRIANGLES (or INDICES),
// others as ATTRIBUTES with their byteStride, element size, or 4.
Bytes meshopt_glb(const Rig& rig, const MeshoptOptions& o = {}) {
  json doc = rig.doc;
  Bytes bin;
  size_t fallback_length = 0;
  const std::map<size_t, ViewUse> uses = view_uses(doc);
  std::set<size_t> images;  // tinygltf reads images while it parses: they stay uncompressed (gltfpack too)
  for (const json& image : doc.value("images", json::array()))
    if (image.contains("bufferView")) images.insert(size_t(image["bufferView"]));
  for (size_t i = 0; i < doc["bufferViews"].size(); ++i) {
    json& view = doc["bufferViews"][i];
    if (images.count(i)) continue;
    const size_t offset = view.value("byteOffset", size_t(0)), length = view["byteLength"];
    const uint8_t* data = rig.bin.data() + offset;
    const auto use = uses.find(i);
    json ext;
    Bytes encoded;
    if (use != uses.end() && use->second.indices) {
      const size_t size = use->second.element, count = length / size;
      std::vector<unsigned> indices(count);
      for (size_t k = 0; k < count; ++k) {
        uint32_t v = 0;
        std::memcpy(&v, data + k * size, size);  // little-endian
        indices[k] = v;
      }
      const bool triangles = o.index_mode == IndexMode::kTriangles && use->second.triangle_indices && count % 3 == 0;
      const size_t vertices = *std::max_element(indices.begin(), indices.end()) + 1;
      encoded.resize(triangles ? meshopt_encodeIndexBufferBound(count, vertices) : meshopt_encodeIndexSequenceBound(count, vertices));
      encoded.resize(triangles ? meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), indices.data(), count)
                               : meshopt_encodeIndexSequence(encoded.data(), encoded.size(), indices.data(), count));
      ext = {{"byteStride", size}, {"count", count}, {"mode", triangles ? "TRIANGLES" : "INDICES"}};
    } else {
      size_t stride = view.value("byteStride", size_t(0));
      if (stride == 0 && use != uses.end() && use->second.element % 4 == 0) stride = use->second.element;
      if (stride == 0 && length % 4 == 0) stride = 4;
      if (stride == 0) continue;  // stays uncompressed, in buffer 0
      const size_t count = length / stride;
      encoded.resize(meshopt_encodeVertexBufferBound(count, stride));
      encoded.resize(meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), data, count, stride));
      ext = {{"byteStride", stride}, {"count", count}, {"mode", "ATTRIBUTES"}};
      if (const auto f = o.filters.find(i); f != o.filters.end()) ext["filter"] = f->second;
    }
    EXPECT_GT(encoded.size(), 0u) << "view " << i;
    pad4(bin);
    ext["buffer"] = 0;
    ext["byteOffset"] = bin.size();
    ext["byteLength"] = encoded.size();
    bin.insert(bin.end(), encoded.begin(), encoded.end());
    fallback_length = (fallback_length + 3) & ~size_t(3);
    view["buffer"] = 1;
    view["byteOffset"] = fallback_length;
    view["extensions"]["EXT_meshopt_compression"] = ext;
    fallback_length += length;
  }
  // Views left uncompressed keep their bytes: they go after the compressed data in buffer 0.
  for (json& view : doc["bufferViews"]) {
    if (view.contains("extensions")) continue;
    pad4(bin);
    const size_t offset = view.value("byteOffset", size_t(0)), length = view["byteLength"];
    view["byteOffset"] = bin.size();
    bin.insert(bin.end(), rig.bin.begin() + std::ptrdiff_t(offset), rig.bin.begin() + std::ptrdiff_t(offset + length));
  }
  pad4(bin);
  json fallback = {{"byteLength", fallback_length}};
  if (o.fallback_flag) fallback["extensions"]["EXT_meshopt_compression"]["fallback"] = true;
  if (o.fallback_data) fallback["uri"] = "data:application/octet-stream;base64," + base64(Bytes(fallback_length, o.fallback_fill));
  doc["buffers"] = json::array({{{"byteLength", bin.size()}}, fallback});
  add_extension(doc, "EXT_meshopt_compression", o.required);
  return glb(doc, bin);
}

const char* const kRigs[] = {"bending_arm.gltf", "textured_cylinder.gltf", "morph_skin.gltf", "eight_influences.gltf",
                             "two_skins.gltf", "interpolation_modes.gltf"};

TEST(Meshopt, LosslessModesLoadExactlyTheUncompressedAsset) {
  for (const char* name : kRigs) {
    SCOPED_TRACE(name);
    const Rig rig = read_rig(name);
    const Asset want = load_rig(rig);
    for (IndexMode mode : {IndexMode::kTriangles, IndexMode::kIndices}) {
      MeshoptOptions o;
      o.index_mode = mode;
      const Asset got = load_bytes(meshopt_glb(rig, o));
      Tolerance exact;
      exact.triangles_up_to_rotation = mode == IndexMode::kTriangles;
      expect_same_asset(want, got, exact);
    }
  }
}

TEST(Meshopt, FallbackBufferIsNotReadEvenWithoutTheFlag) {
  const Rig rig = read_rig("textured_cylinder.gltf");
  const Asset want = load_rig(rig);
  // gltfpack's placeholder: buffer 1 without uri and without the fallback flag. tinygltf alone would copy
  // the BIN chunk into it.
  MeshoptOptions o;
  o.fallback_flag = false;
  Tolerance exact;
  exact.triangles_up_to_rotation = true;
  expect_same_asset(want, load_bytes(meshopt_glb(rig, o)), exact);
  // Only used, not required, with a fallback that has data: the views are still decoded (the fallback's
  // bytes here are not the rig's, so reading them would fail the comparison).
  o.required = false;
  o.fallback_flag = true;
  o.fallback_data = true;
  o.fallback_fill = 0x7f;
  const Asset got = load_bytes(meshopt_glb(rig, o));
  expect_same_asset(want, got, exact);
  EXPECT_TRUE(std::none_of(got.warnings.begin(), got.warnings.end(),
                           [](const std::string& w) { return w.find("EXT_meshopt_compression") != std::string::npos; }));
}

TEST(Meshopt, GltfWithDataUriBuffersLoadsToo) {
  const Rig rig = read_rig("bending_arm.gltf");
  const Bytes file = meshopt_glb(rig);
  // The same document as .gltf: the compressed buffer as a data URI, the fallback without uri.
  const uint32_t json_length = uint32_t(file[12]) | uint32_t(file[13]) << 8 | uint32_t(file[14]) << 16 | uint32_t(file[15]) << 24;
  json doc = json::parse(file.begin() + 20, file.begin() + 20 + json_length);
  const Bytes bin(file.begin() + 20 + json_length + 8, file.end());
  doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(bin);
  const std::string text = doc.dump();
  Tolerance exact;
  exact.triangles_up_to_rotation = true;
  expect_same_asset(load_rig(rig), load_bytes(Bytes(text.begin(), text.end())), exact);
}

// Filters trade precision for size; the rig is re-quantized the way gltfpack does before filtering.
TEST(Meshopt, FiltersDecodeWithinTheirQuantization) {
  for (const char* name : {"textured_cylinder.gltf", "bending_arm.gltf"}) {
    SCOPED_TRACE(name);
    Rig rig = read_rig(name);
    const Asset want = load_rig(rig);
    MeshoptOptions o;
    json& doc = rig.doc;
    auto replace_view = [&](size_t accessor, const Bytes& data, size_t stride) {
      pad4(rig.bin);
      doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", rig.bin.size()}, {"byteLength", data.size()}, {"byteStride", stride}});
      rig.bin.insert(rig.bin.end(), data.begin(), data.end());
      doc["accessors"][accessor]["bufferView"] = doc["bufferViews"].size() - 1;
      doc["accessors"][accessor].erase("byteOffset");
      return doc["bufferViews"].size() - 1;
    };
    auto floats_of = [&](size_t accessor) {
      const json& a = doc["accessors"][accessor];
      const json& v = doc["bufferViews"][size_t(a["bufferView"])];
      const size_t n = size_t(a["count"]) * components(a["type"]);
      std::vector<float> out(n);
      std::memcpy(out.data(), rig.bin.data() + v.value("byteOffset", size_t(0)) + a.value("byteOffset", size_t(0)), n * 4);
      return out;
    };
    const json& prim = doc["meshes"][0]["primitives"][0];
    // NORMAL: octahedral, 16-bit components (stride 8), 15 bits of X/Y. Each of X and Y is off by at most
    // half a step of 2 / (2^14 - 1) before renormalisation, the 16-bit output by half of 1 / 32767: the
    // direction by less than 2e-4.
    {
      const size_t n = prim["attributes"]["NORMAL"];
      std::vector<float> v = floats_of(n), v4;
      for (size_t i = 0; i < v.size(); i += 3) v4.insert(v4.end(), {v[i], v[i + 1], v[i + 2], 1.0f});
      Bytes data(v4.size() / 4 * 8);
      meshopt_encodeFilterOct(data.data(), v4.size() / 4, 8, 15, v4.data());
      o.filters[replace_view(n, data, 8)] = "OCTAHEDRAL";
      doc["accessors"][n]["componentType"] = 5122;
      doc["accessors"][n]["normalized"] = true;
    }
    // POSITION: exponential, 16-bit signed mantissa, one exponent per vector: the smallest power of two
    // that fits the largest component in the mantissa, so the step is under 2 |max| / 2^15 and each
    // component is off by at most half of it, |max| × 2^-15: the vector by sqrt(3) times that.
    float largest = 0;
    {
      const size_t n = prim["attributes"]["POSITION"];
      const std::vector<float> v = floats_of(n);
      for (float x : v) largest = std::max(largest, std::abs(x));
      Bytes data(v.size() * 4);
      meshopt_encodeFilterExp(data.data(), v.size() / 3, 12, 16, v.data());
      o.filters[replace_view(n, data, 12)] = "EXPONENTIAL";
    }
    // Rotation keys: quaternion filter, 16-bit (stride 8) with 12 bits per component: each stored
    // component is within half a step of sqrt(2) / (2^11 - 1) · ... of the original; 1e-3 covers it with
    // the reconstructed fourth component. The filter makes the largest component positive, so q may come
    // back as -q.
    for (const json& sampler : doc["animations"][0]["samplers"]) {
      const size_t out = sampler["output"];
      if (doc["accessors"][out]["type"] != "VEC4" || sampler.value("interpolation", "LINEAR") == "CUBICSPLINE") continue;
      const std::vector<float> v = floats_of(out);
      Bytes data(v.size() / 4 * 8);
      meshopt_encodeFilterQuat(data.data(), v.size() / 4, 8, 12, v.data());
      o.filters[replace_view(out, data, 8)] = "QUATERNION";
      doc["accessors"][out]["componentType"] = 5122;
      doc["accessors"][out]["normalized"] = true;
    }
    add_extension(doc, "KHR_mesh_quantization", true);
    Tolerance t;
    t.normals = 2e-4f;
    t.positions = largest * 0x1p-15f * 1.74f;
    t.keys = 1e-3f;
    t.rotations_up_to_sign = true;
    t.triangles_up_to_rotation = true;
    const Asset got = load_bytes(meshopt_glb(rig, o));
    expect_same_asset(want, got, t);
    // The filters were really applied: a NONE filter on the same data gives other values.
    for (auto& [view, filter] : o.filters) filter = "NONE";
    const Asset unfiltered = load_bytes(meshopt_glb(rig, o));
    EXPECT_NE(unfiltered.meshes[0].primitives[0].positions, got.meshes[0].primitives[0].positions);
  }
}

// Each case edits the compressed file's JSON (or its data) and names the message's start.
struct BadCase {
  const char* name;
  std::function<void(json& doc, Bytes& bin)> edit;
  const char* message;
};

TEST(Meshopt, MalformedDataAndLayoutsAreOneLineInputErrors) {
  const Rig rig = read_rig("bending_arm.gltf");
  const Bytes file = meshopt_glb(rig);
  const uint32_t json_length = uint32_t(file[12]) | uint32_t(file[13]) << 8 | uint32_t(file[14]) << 16 | uint32_t(file[15]) << 24;
  const json doc0 = json::parse(file.begin() + 20, file.begin() + 20 + json_length);
  const Bytes bin0(file.begin() + 20 + json_length + 8, file.end());
  // The POSITION view, compressed as ATTRIBUTES, and the indices view, as TRIANGLES.
  const size_t pos_view = doc0["accessors"][size_t(doc0["meshes"][0]["primitives"][0]["attributes"]["POSITION"])]["bufferView"];
  const size_t idx_view = doc0["accessors"][size_t(doc0["meshes"][0]["primitives"][0]["indices"])]["bufferView"];
  const std::string pv = "bufferView " + std::to_string(pos_view) + ": EXT_meshopt_compression ";
  const std::string iv = "bufferView " + std::to_string(idx_view) + ": EXT_meshopt_compression ";
  auto ext = [](json& doc, size_t view) -> json& { return doc["bufferViews"][view]["extensions"]["EXT_meshopt_compression"]; };
  const std::vector<BadCase> cases = {
      {"truncated stream", [&](json& d, Bytes&) { ext(d, pos_view)["byteLength"] = size_t(ext(d, pos_view)["byteLength"]) / 2; },
       "data is malformed (ATTRIBUTES decoder error"},
      {"wrong header byte", [&](json& d, Bytes& b) { b[size_t(ext(d, pos_view)["byteOffset"])] = 0x55; },
       "data is malformed (header byte 0x55 does not start ATTRIBUTES data"},
      {"attributes read as indices", [&](json& d, Bytes&) { ext(d, pos_view)["mode"] = "INDICES", ext(d, pos_view)["byteStride"] = 4,
                                                             ext(d, pos_view)["count"] = size_t(d["bufferViews"][pos_view]["byteLength"]) / 4; },
       "data is malformed (header byte 0xa0 does not start INDICES data"},
      {"garbage triangles", [&](json& d, Bytes& b) {
         const size_t at = ext(d, idx_view)["byteOffset"], n = ext(d, idx_view)["byteLength"];
         for (size_t k = 1; k < n; ++k) b[at + k] = uint8_t(k * 37);
       }, "data is malformed (TRIANGLES decoder error"},
      {"count mismatch", [&](json& d, Bytes&) { ext(d, pos_view)["count"] = size_t(ext(d, pos_view)["count"]) - 1; },
       "holds "},
      {"stride mismatch", [&](json& d, Bytes&) { ext(d, pos_view)["byteStride"] = 16; },
       "holds "},
      {"stride not a multiple of 4", [&](json& d, Bytes&) {
         ext(d, pos_view)["byteStride"] = 6, ext(d, pos_view)["count"] = size_t(d["bufferViews"][pos_view]["byteLength"]) / 6; },
       "byteStride 6 must be a multiple of 4 (up to 256) in ATTRIBUTES mode"},
      {"index stride", [&](json& d, Bytes&) { ext(d, idx_view)["byteStride"] = 1, ext(d, idx_view)["count"] = size_t(d["bufferViews"][idx_view]["byteLength"]); },
       "byteStride 1 must be 2 or 4 in TRIANGLES mode"},
      {"filter on indices", [&](json& d, Bytes&) { ext(d, idx_view)["filter"] = "OCTAHEDRAL"; },
       "filter OCTAHEDRAL is not allowed in TRIANGLES mode"},
      {"quaternion filter on 12-byte elements", [&](json& d, Bytes&) { ext(d, pos_view)["filter"] = "QUATERNION"; },
       "filter QUATERNION does not allow byteStride 12 (8)"},
      {"unknown mode", [&](json& d, Bytes&) { ext(d, pos_view)["mode"] = "ZSTD"; }, "mode \"ZSTD\" must be"},
      {"unknown filter", [&](json& d, Bytes&) { ext(d, pos_view)["filter"] = 2; }, "filter 2 must be"},
      {"missing count", [&](json& d, Bytes&) { ext(d, pos_view).erase("count"); }, "bufferView"},
      {"range past its buffer", [&](json& d, Bytes&) { ext(d, pos_view)["byteOffset"] = 1u << 30; }, "data (offset 1073741824"},
      {"compressed data in the fallback", [&](json& d, Bytes&) { ext(d, pos_view)["buffer"] = 1; }, "buffer 1 has no data"},
      {"parent stride differs", [&](json& d, Bytes&) { d["bufferViews"][pos_view]["byteStride"] = 16; },
       "byteStride 12 differs from the view's byteStride 16"},
  };
  for (const BadCase& c : cases) {
    json doc = doc0;
    Bytes bin = bin0;
    c.edit(doc, bin);
    const std::string message = load_error(glb(doc, bin));
    EXPECT_NE(message.find(c.message), std::string::npos) << c.name << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << c.name << ": " << message;
  }
  // An uncompressed view in the fallback buffer has nothing to read.
  json doc = doc0;
  doc["bufferViews"][pos_view].erase("extensions");
  EXPECT_EQ(load_error(glb(doc, bin0)).rfind("bufferView " + std::to_string(pos_view) + ": buffer 1 has no data", 0), 0u)
      << load_error(glb(doc, bin0));
  // Schema ranges of the extension's integers.
  doc = doc0;
  ext(doc, pos_view)["byteStride"] = 260;
  EXPECT_EQ(load_error(glb(doc, bin0)),
            "bufferView " + std::to_string(pos_view) + ": extensions.EXT_meshopt_compression.byteStride 260 must be an integer from 1 to 256");
  (void)pv, (void)iv;
}

TEST(Meshopt, DecodedSizesCountTowardMaxMemoryBeforeAnythingIsDecoded) {
  const Rig rig = read_rig("bending_arm.gltf");
  const Bytes file = meshopt_glb(rig);
  LoadOptions tight;
  tight.max_memory = 160 << 10;
  // The fallback buffer claims 3 GB of decoded views: refused in the precheck, from the declared sizes.
  const uint32_t json_length = uint32_t(file[12]) | uint32_t(file[13]) << 8 | uint32_t(file[14]) << 16 | uint32_t(file[15]) << 24;
  json doc = json::parse(file.begin() + 20, file.begin() + 20 + json_length);
  const Bytes bin(file.begin() + 20 + json_length + 8, file.end());
  doc["buffers"][1]["byteLength"] = 3000000000ull;
  json& view = doc["bufferViews"][0];
  auto& e = view["extensions"]["EXT_meshopt_compression"];
  e["count"] = 3000000000ull / size_t(e["byteStride"]);
  view["byteLength"] = size_t(e["count"]) * size_t(e["byteStride"]);
  const std::string message = load_error(glb(doc, bin));
  EXPECT_NE(message.find("of EXT_meshopt_compression views decoded"), std::string::npos) << message;
  EXPECT_NE(message.find("more than --max-memory"), std::string::npos) << message;
  // The real file: its decoded views are part of the estimate the loader checks after parsing.
  const uint64_t decoded = [&] {
    uint64_t sum = 0;
    const json d = json::parse(file.begin() + 20, file.begin() + 20 + json_length);
    for (const json& v : d["bufferViews"])
      if (v.contains("extensions")) sum += size_t(v["byteLength"]);
    return sum;
  }();
  EXPECT_GT(decoded, 0u);
  EXPECT_NE(load_error(file, tight).find(" decoded, "), std::string::npos) << load_error(file, tight);
}

// ---------------------------------------------------------------------------------------------------
// KHR_draco_mesh_compression, as gltf-transform writes it: each primitive's attributes and indices one
// Draco mesh in a view of buffer 0; the accessors keep count and type but lose their bufferView.

struct DracoOptions {
  int method = draco::MESH_SEQUENTIAL_ENCODING;  // keeps the points in order (edgebreaker reorders them)
  int position_bits = 0, normal_bits = 0, texcoord_bits = 0;  // 0: not quantized (lossless)
  int unlisted_components = 0;  // > 0: one more float attribute, of so many components, that the extension does not list
};

draco::DataType draco_type(int component_type) {
  switch (component_type) {
    case 5120: return draco::DT_INT8;
    case 5121: return draco::DT_UINT8;
    case 5122: return draco::DT_INT16;
    case 5123: return draco::DT_UINT16;
    case 5125: return draco::DT_UINT32;
    default: return draco::DT_FLOAT32;
  }
}

// The rig with every primitive's attributes (not its morph targets) and indices Draco-compressed.
Rig draco_rig(const Rig& rig, const DracoOptions& o = {}) {
  Rig out{rig.doc, rig.bin};
  json& doc = out.doc;
  auto element_at = [&](const json& a, size_t i) {
    const json& v = rig.doc["bufferViews"][size_t(a["bufferView"])];
    const size_t size = component_size(a["componentType"]) * components(a["type"]);
    const size_t stride = v.value("byteStride", size);
    return rig.bin.data() + v.value("byteOffset", size_t(0)) + a.value("byteOffset", size_t(0)) + i * stride;
  };
  for (json& mesh : doc["meshes"])
    for (json& p : mesh["primitives"]) {
      draco::Mesh dm;
      const json& ia = doc["accessors"][size_t(p["indices"])];
      const size_t corners = ia["count"];
      const json& pa = doc["accessors"][size_t(p["attributes"]["POSITION"])];
      const size_t points = pa["count"];
      dm.set_num_points(uint32_t(points));
      for (size_t f = 0; f < corners / 3; ++f) {
        draco::Mesh::Face face;
        for (size_t c = 0; c < 3; ++c) {
          uint32_t v = 0;
          std::memcpy(&v, element_at(ia, 3 * f + c), component_size(ia["componentType"]));
          face[c] = draco::PointIndex(v);
        }
        dm.AddFace(face);
      }
      json ids = json::object();
      for (auto& [name, index] : p["attributes"].items()) {
        json& a = doc["accessors"][size_t(index)];
        const auto type = name == "POSITION" ? draco::GeometryAttribute::POSITION
                          : name == "NORMAL" ? draco::GeometryAttribute::NORMAL
                          : name.rfind("TEXCOORD_", 0) == 0 ? draco::GeometryAttribute::TEX_COORD
                          : name.rfind("COLOR_", 0) == 0 ? draco::GeometryAttribute::COLOR
                                                           : draco::GeometryAttribute::GENERIC;
        const size_t n = components(a["type"]), size = component_size(a["componentType"]) * n;
        draco::GeometryAttribute ga;
        ga.Init(type, nullptr, uint8_t(n), draco_type(a["componentType"]), a.value("normalized", false), int64_t(size), 0);
        const int id = dm.AddAttribute(ga, true, uint32_t(points));
        for (size_t i = 0; i < points; ++i) dm.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(uint32_t(i)), element_at(a, i));
        ids[name] = dm.attribute(id)->unique_id();
        a.erase("bufferView");
        a.erase("byteOffset");
      }
      if (o.unlisted_components > 0) {
        draco::GeometryAttribute ga;
        ga.Init(draco::GeometryAttribute::GENERIC, nullptr, uint8_t(o.unlisted_components), draco::DT_FLOAT32, false,
                int64_t(4 * o.unlisted_components), 0);
        const int id = dm.AddAttribute(ga, true, uint32_t(points));
        const std::vector<float> zeros(size_t(o.unlisted_components), 0.0f);
        for (size_t i = 0; i < points; ++i) dm.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(uint32_t(i)), zeros.data());
      }
      draco::Encoder encoder;
      encoder.SetEncodingMethod(o.method);
      if (o.position_bits) encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, o.position_bits);
      if (o.normal_bits) encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, o.normal_bits);
      if (o.texcoord_bits) encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, o.texcoord_bits);
      draco::EncoderBuffer encoded;
      const draco::Status status = encoder.EncodeMeshToBuffer(dm, &encoded);
      EXPECT_TRUE(status.ok()) << status.error_msg_string();
      pad4(out.bin);
      doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", out.bin.size()}, {"byteLength", encoded.size()}});
      out.bin.insert(out.bin.end(), encoded.data(), encoded.data() + encoded.size());
      doc["accessors"][size_t(p["indices"])].erase("bufferView");
      doc["accessors"][size_t(p["indices"])].erase("byteOffset");
      p["extensions"]["KHR_draco_mesh_compression"] = {{"bufferView", doc["bufferViews"].size() - 1}, {"attributes", ids}};
    }
  pad4(out.bin);
  doc["buffers"][0]["byteLength"] = out.bin.size();
  add_extension(doc, "KHR_draco_mesh_compression", true);
  return out;
}

TEST(Draco, LosslessSequentialMeshesLoadExactlyTheUncompressedAsset) {
  for (const char* name : kRigs) {
    SCOPED_TRACE(name);
    const Rig rig = read_rig(name);
    expect_same_asset(load_rig(rig), load_rig(draco_rig(rig)));
  }
}

// Quantized attributes come back on the quantization grid: Draco spreads 2^bits - 1 steps over the
// largest extent of the attribute's bounding box, so each component is off by at most half a step (the
// vector by sqrt(3) / 2 steps). Normals are octahedral with `normal_bits` per coordinate: a step of
// 2 / (2^bits - 1) in the octahedron's square; half a step in each coordinate, stretched by up to sqrt(2)
// where the square folds onto the sphere, is within one step of the direction (a quarter more for the
// float rounding of the renormalised result).
TEST(Draco, QuantizedAttributesDecodeWithinTheirStep) {
  for (const char* name : {"textured_cylinder.gltf", "morph_skin.gltf"}) {
    SCOPED_TRACE(name);
    const Rig rig = read_rig(name);
    const Asset want = load_rig(rig);
    DracoOptions o;
    o.position_bits = 14;
    o.normal_bits = 12;
    o.texcoord_bits = 12;
    const Asset got = load_rig(draco_rig(rig, o));
    float extent = 0, uv_extent = 0;
    for (const Mesh& m : want.meshes)
      for (const Primitive& p : m.primitives) {
        glm::vec3 lo(1e30f), hi(-1e30f);
        for (const glm::vec3& v : p.positions) lo = glm::min(lo, v), hi = glm::max(hi, v);
        extent = std::max({extent, hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
        glm::vec2 ulo(1e30f), uhi(-1e30f);
        for (const glm::vec2& v : p.uv0) ulo = glm::min(ulo, v), uhi = glm::max(uhi, v);
        if (!p.uv0.empty()) uv_extent = std::max({uv_extent, uhi.x - ulo.x, uhi.y - ulo.y});
      }
    Tolerance t;
    t.positions = extent / float((1 << 14) - 1) * 0.87f * 1.01f;
    t.uv = uv_extent / float((1 << 12) - 1) * 0.71f * 1.01f;
    t.normals = 1.25f * 2.0f / float((1 << 12) - 1);
    expect_same_asset(want, got, t);
  }
}

TEST(Draco, MalformedDataIsAOneLineInputError) {
  const Rig compressed = draco_rig(read_rig("bending_arm.gltf"));
  const json& ext0 = compressed.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"];
  const size_t view = ext0["bufferView"];
  const size_t position = compressed.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
  const std::string prefix = "mesh 0 primitive 0: KHR_draco_mesh_compression ";
  auto error = [](const Rig& r) { return load_error(glb(r.doc, r.bin)); };
  {  // garbage after the header: the counts it claims are checked first
    Rig r = compressed;
    const size_t at = r.doc["bufferViews"][view]["byteOffset"], n = r.doc["bufferViews"][view]["byteLength"];
    for (size_t k = 11; k < n; ++k) r.bin[at + k] = uint8_t(k * 131 + 7);
    EXPECT_EQ(error(r).rfind(prefix + "indices: accessor ", 0), 0u) << error(r);
    EXPECT_NE(error(r).find(", the compressed data "), std::string::npos) << error(r);
  }
  {  // garbage after the connectivity's counts (faces and points, 2-byte varints here, and its method byte)
    Rig r = compressed;
    const size_t at = r.doc["bufferViews"][view]["byteOffset"], n = r.doc["bufferViews"][view]["byteLength"];
    for (size_t k = 16; k < n; ++k) r.bin[at + k] = uint8_t(k * 131 + 7);
    EXPECT_EQ(error(r).rfind(prefix + "data is malformed (", 0), 0u) << error(r);
  }
  {  // not Draco at all
    Rig r = compressed;
    const size_t at = r.doc["bufferViews"][view]["byteOffset"];
    std::memcpy(&r.bin[at], "GARBAGE!", 8);
    EXPECT_EQ(error(r).rfind(prefix + "data is malformed (", 0), 0u) << error(r);
  }
  {  // truncated
    Rig r = compressed;
    r.doc["bufferViews"][view]["byteLength"] = size_t(r.doc["bufferViews"][view]["byteLength"]) / 2;
    EXPECT_EQ(error(r).rfind(prefix + "data is malformed (", 0), 0u) << error(r);
  }
  {  // a unique id the data does not have
    Rig r = compressed;
    r.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["POSITION"] = 99;
    EXPECT_EQ(error(r), prefix + "attribute POSITION: unique id 99 is not in the compressed data");
  }
  {  // the accessor's count is not the decoded point count
    Rig r = compressed;
    r.doc["accessors"][position]["count"] = size_t(r.doc["accessors"][position]["count"]) + 1;
    EXPECT_NE(error(r).find("attribute POSITION: accessor " + std::to_string(position) + " has count"), std::string::npos) << error(r);
  }
  {  // the accessor's type does not match the data's components
    Rig r = compressed;
    r.doc["accessors"][position]["type"] = "VEC4";
    EXPECT_EQ(error(r), prefix + "attribute POSITION has 3 components in the compressed data, its accessor 4");
  }
  {  // an attribute name the primitive does not have
    Rig r = compressed;
    r.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["TEXCOORD_3"] = 0;
    EXPECT_EQ(error(r), prefix + "attribute TEXCOORD_3 is not an attribute of the primitive");
  }
}

// A stream's counts are checked against the accessors before libdraco allocates for them: a header that
// claims 1.4 billion triangles (libdraco would allocate a 17 GB corner table for them, before it reads
// a symbol) is refused by its count alone.
TEST(Draco, HugeCountsInTheStreamAreRefusedBeforeDecoding) {
  DracoOptions edgebreaker;
  edgebreaker.method = draco::MESH_EDGEBREAKER_ENCODING;
  const Rig compressed = draco_rig(read_rig("bending_arm.gltf"), edgebreaker);
  EXPECT_EQ(load_error(glb(compressed.doc, compressed.bin)), "(loaded)");  // the stream as the encoder wrote it
  const json& p = compressed.doc["meshes"][0]["primitives"][0];
  const size_t view = p["extensions"]["KHR_draco_mesh_compression"]["bufferView"];
  const size_t indices = p["indices"];
  const size_t at = compressed.doc["bufferViews"][view]["byteOffset"];
  ASSERT_EQ(compressed.bin[at + 8], draco::MESH_EDGEBREAKER_ENCODING);
  auto varint = [](Bytes& out, uint32_t v) {
    for (; v > 0x7F; v >>= 7) out.push_back(uint8_t(v | 0x80));
    out.push_back(uint8_t(v));
  };
  // The header (11 bytes) and the traversal type, then vertices, faces, attribute connectivities, symbols
  // and split symbols as libdraco checks them (vertices <= 3 faces, symbols <= faces <= 4/3 symbols).
  Bytes stream(compressed.bin.begin() + long(at), compressed.bin.begin() + long(at) + 12);
  const uint32_t faces = 0x55555555;
  varint(stream, faces);
  varint(stream, faces);
  stream.push_back(0);
  varint(stream, faces);
  varint(stream, 0);
  stream.resize(stream.size() + 64, 0);
  Rig r = compressed;
  pad4(r.bin);
  r.doc["bufferViews"][view]["byteOffset"] = r.bin.size();
  r.doc["bufferViews"][view]["byteLength"] = stream.size();
  r.bin.insert(r.bin.end(), stream.begin(), stream.end());
  pad4(r.bin);
  r.doc["buffers"][0]["byteLength"] = r.bin.size();
  const size_t index_count = compressed.doc["accessors"][indices]["count"];
  EXPECT_EQ(load_error(glb(r.doc, r.bin)),
            "mesh 0 primitive 0: KHR_draco_mesh_compression indices: accessor " + std::to_string(indices) +
                " has count " + std::to_string(index_count) + ", the compressed data 1431655765 triangles (4294967295 indices)");
}

// Attributes the extension does not list are decoded too: within what the listed ones leave, they load;
// beyond it (as many components as a hostile stream likes, up to 255 each) they are refused.
TEST(Draco, UnlistedAttributesAreBoundedByTheListedOnes) {
  const Rig rig = read_rig("bending_arm.gltf");
  DracoOptions small, large;
  small.unlisted_components = 2;
  large.unlisted_components = 64;
  expect_same_asset(load_rig(rig), load_rig(draco_rig(rig, small)));
  const Rig r = draco_rig(rig, large);
  const std::string error = load_error(glb(r.doc, r.bin));
  EXPECT_EQ(error.rfind("mesh 0 primitive 0: KHR_draco_mesh_compression data is malformed (its 5 attributes take ", 0), 0u) << error;
  EXPECT_NE(error.find("of the attributes the extension lists)"), std::string::npos) << error;
}

// The frame writer copies TEXCOORD_n and COLOR_n from the source: decoded, they are there to copy.
TEST(Draco, KeptSourceHasTheDecodedTexcoordsAndColors) {
  const Rig rig = read_rig("textured_cylinder.gltf");
  LoadOptions keep;
  keep.keep_source = true;
  const Asset want = load_bytes(glb(rig.doc, rig.bin), keep);
  const Rig compressed = draco_rig(rig);
  const Asset got = load_bytes(glb(compressed.doc, compressed.bin), keep);
  ASSERT_TRUE(want.source && got.source);
  ASSERT_EQ(want.source->meshes.size(), got.source->meshes.size());
  for (size_t m = 0; m < want.source->meshes.size(); ++m)
    for (size_t p = 0; p < want.source->meshes[m].size(); ++p) {
      const SourcePrimitive& a = want.source->meshes[m][p];
      const SourcePrimitive& b = got.source->meshes[m][p];
      EXPECT_EQ(b.error, "");
      ASSERT_EQ(a.attributes.size(), b.attributes.size());
      for (size_t k = 0; k < a.attributes.size(); ++k) {
        EXPECT_EQ(a.attributes[k].name, b.attributes[k].name);
        EXPECT_EQ(a.attributes[k].values, b.attributes[k].values) << a.attributes[k].name;
      }
    }
}

// A frame of each compressed input goes through the frame writer's checks and into glb_samples (named
// GlbOutput.* for that test's filter), for the glb_validator test: the writer copies TEXCOORD_n and COLOR_n
// from what the codecs decoded.
TEST(GlbOutput, CompressedInputsRoundTrip) {
  const fs::path dir = fs::temp_directory_path() / ("dqskin_compressed_frames_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const Rig rig = read_rig("textured_cylinder.gltf");
  const Rig draco = draco_rig(rig);
  const std::vector<std::pair<std::string, Bytes>> inputs = {{"draco_textured_cylinder", glb(draco.doc, draco.bin)},
                                                             {"meshopt_textured_cylinder", meshopt_glb(rig)}};
  for (const auto& [name, bytes] : inputs) {
    const fs::path path = dir / (name + ".glb");
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    glb_check::check_model(path.string(), name);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace dqskin
