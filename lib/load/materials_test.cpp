// Materials as the loader reads them (lib/load/materials.cpp): KHR_texture_transform on the base color
// texture, its defaults, its texCoord override, and bad values dropped with a warning; which image a
// texture draws under EXT_texture_webp and KHR_texture_basisu.
#include "dqskin/load.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace dqskin {
namespace {

using nlohmann::json;

// A file with one material whose base color texture (index 0, TEXCOORD_0) carries `transform` as its
// KHR_texture_transform, or none when it is null. No meshes: the materials are read all the same.
Asset load_with_transform(const json& transform, const json& texture_info_extra = json::object()) {
  json info = {{"index", 0}};
  info.update(texture_info_extra);
  if (!transform.is_null()) info["extensions"]["KHR_texture_transform"] = transform;
  json doc = {{"asset", {{"version", "2.0"}}},
              {"extensionsUsed", {"KHR_texture_transform"}},
              {"materials", {{{"name", "m"}, {"pbrMetallicRoughness", {{"baseColorTexture", info}}}}}},
              {"textures", {{{"source", 0}}}},
              // A PNG signature is enough: the loader keeps the bytes, only the renderer decodes them.
              {"images", {{{"uri", "data:image/png;base64,iVBORw0KGgo="}}}}};
  const std::string text = doc.dump();
  return load_asset_from_memory(std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()), "test", ".");
}

std::string all_warnings(const Asset& asset) {
  std::string out;
  for (const std::string& w : asset.warnings) out += "\n  " + w;
  return out;
}

void expect_identity(const TextureTransform& t) {
  EXPECT_EQ(t.offset, glm::vec2(0.0f));
  EXPECT_EQ(t.rotation, 0.0f);
  EXPECT_EQ(t.scale, glm::vec2(1.0f));
  EXPECT_EQ(t.matrix(), glm::mat3(1.0f)) << "exactly the identity, so files without the extension draw as before";
}

TEST(TextureTransform, AbsentOrEmptyIsTheIdentity) {
  for (const json& transform : {json(), json::object()}) {
    const Asset asset = load_with_transform(transform);
    ASSERT_EQ(asset.materials.size(), 1u);
    const TextureRef& ref = asset.materials[0].base_color_texture;
    EXPECT_EQ(ref.texture, 0);
    EXPECT_EQ(ref.texcoord, 0);
    expect_identity(ref.transform);
    EXPECT_TRUE(asset.warnings.empty()) << all_warnings(asset);
  }
}

TEST(TextureTransform, EachValueIsReadAndTheOthersKeepTheirDefaults) {
  Asset asset = load_with_transform({{"rotation", 0.5}});
  EXPECT_EQ(asset.materials[0].base_color_texture.transform.rotation, 0.5f);
  EXPECT_EQ(asset.materials[0].base_color_texture.transform.offset, glm::vec2(0.0f));
  EXPECT_EQ(asset.materials[0].base_color_texture.transform.scale, glm::vec2(1.0f));
  EXPECT_TRUE(asset.warnings.empty()) << all_warnings(asset);

  // Integers are numbers too (tinygltf keeps them apart from reals).
  asset = load_with_transform({{"offset", {0, 1}}, {"scale", {0.5, -2}}, {"rotation", 3}});
  const TextureTransform& t = asset.materials[0].base_color_texture.transform;
  EXPECT_EQ(t.offset, glm::vec2(0, 1));
  EXPECT_EQ(t.scale, glm::vec2(0.5f, -2.0f));
  EXPECT_EQ(t.rotation, 3.0f);
  EXPECT_EQ(asset.materials[0].base_color_texture.texcoord, 0) << "no texCoord: the textureInfo's";
  EXPECT_TRUE(asset.warnings.empty()) << "the extension is applied now, so nothing to warn about:" << all_warnings(asset);
}

TEST(TextureTransform, TexCoordOverridesTheTextureInfos) {
  Asset asset = load_with_transform({{"texCoord", 1}});
  EXPECT_EQ(asset.materials[0].base_color_texture.texcoord, 1);
  expect_identity(asset.materials[0].base_color_texture.transform);

  asset = load_with_transform({{"texCoord", 0}, {"offset", {0.25, 0}}}, {{"texCoord", 1}});
  EXPECT_EQ(asset.materials[0].base_color_texture.texcoord, 0) << "the override wins, also back to 0";
  EXPECT_EQ(asset.materials[0].base_color_texture.transform.offset, glm::vec2(0.25f, 0.0f));

  // A set the renderer does not read: the existing warning, naming the set the override chose.
  asset = load_with_transform({{"texCoord", 2}});
  EXPECT_EQ(asset.materials[0].base_color_texture.texcoord, 2);
  ASSERT_EQ(asset.warnings.size(), 1u) << all_warnings(asset);
  EXPECT_NE(asset.warnings[0].find("reads TEXCOORD_2"), std::string::npos) << asset.warnings[0];
}

// A bad value drops the whole transform (texCoord included) with a warning; the texture stays.
TEST(TextureTransform, BadValuesDropTheTransformWithAWarning) {
  const std::string where = "material 0 baseColorTexture: KHR_texture_transform ";
  const std::string ignored = "; the transform is ignored";
  const std::vector<std::pair<json, std::string>> cases = {
      {{{"offset", {1}}}, where + "offset must be 2 finite numbers" + ignored},
      {{{"offset", {1, 2, 3}}}, where + "offset must be 2 finite numbers" + ignored},
      {{{"offset", "1, 2"}}, where + "offset must be 2 finite numbers" + ignored},
      {{{"offset", {1, "2"}}}, where + "offset must be 2 finite numbers" + ignored},
      {{{"offset", {nullptr, 2}}}, where + "offset must be 2 finite numbers" + ignored},
      {{{"scale", {1e39, 1}}}, where + "scale must be 2 finite numbers" + ignored},  // infinite as a float
      {{{"scale", {true, false}}}, where + "scale must be 2 finite numbers" + ignored},
      {{{"scale", 2}}, where + "scale must be 2 finite numbers" + ignored},
      {{{"rotation", "0.5"}}, where + "rotation must be a finite number" + ignored},
      {{{"rotation", {0.5}}}, where + "rotation must be a finite number" + ignored},
      {{{"rotation", -1e300}}, where + "rotation must be a finite number" + ignored},
      // texCoord is checked on the JSON with the other indices (schema_values.cpp).
      {{{"texCoord", -1}}, "material 0: pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform.texCoord"},
      {{{"texCoord", 1.5}}, "material 0: pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform.texCoord"},
  };
  for (const auto& [bad, expected_text] : cases) {
    const std::string& expected = expected_text;  // a lambda captures a variable, not a structured binding
    json transform = bad;
    transform["texCoord"] = transform.value("texCoord", json(1));  // dropped with the rest
    transform["offset"] = transform.value("offset", json{0.5, 0.5});
    const Asset asset = load_with_transform(transform);
    const TextureRef& ref = asset.materials[0].base_color_texture;
    const bool warned = std::any_of(asset.warnings.begin(), asset.warnings.end(),
                                    [&](const std::string& w) { return w.find(expected) != std::string::npos; });
    EXPECT_TRUE(warned) << bad.dump() << ": expected " << expected << "\nwarnings:" << all_warnings(asset);
    EXPECT_EQ(asset.warnings.size(), 1u) << bad.dump() << all_warnings(asset);
    EXPECT_EQ(ref.texture, 0) << bad.dump() << ": the texture is still drawn";
    EXPECT_EQ(ref.texcoord, 0) << bad.dump() << ": the override is dropped too";
    expect_identity(ref.transform);
  }
}

// uv' = T · R · S · uv. The extension's example: offset (0, 1), rotation 90°, scale 0.5 "utilizes only the
// lower left quadrant of the source image, rotated clockwise 90°" (UV (0, 0) is the image's top-left).
TEST(TextureTransform, MatrixIsTranslationRotationScaleAsTheExtensionsExampleSays) {
  TextureTransform t;
  t.offset = {0, 1};
  t.rotation = float(std::numbers::pi / 2);
  t.scale = {0.5f, 0.5f};
  const glm::mat3 m = t.matrix();
  auto at = [&](float u, float v) { return glm::vec2(m * glm::vec3(u, v, 1)); };
  auto near = [](glm::vec2 a, glm::vec2 b) { return glm::all(glm::lessThan(glm::abs(a - b), glm::vec2(1e-6f))); };
  // The surface's UV corners land on the lower-left quadrant [0, 0.5] x [0.5, 1]: the surface's top-left
  // shows the quadrant's bottom-left, its top-right the quadrant's top-left (turned clockwise).
  EXPECT_TRUE(near(at(0, 0), {0, 1}));
  EXPECT_TRUE(near(at(1, 0), {0, 0.5f}));
  EXPECT_TRUE(near(at(1, 1), {0.5f, 0.5f}));
  EXPECT_TRUE(near(at(0, 1), {0.5f, 1}));

  // Scale applies before rotation (T · R · S, not T · S · R): with scale (2, 1) and a quarter turn, u
  // (scaled by 2) becomes -v'.
  t = {};
  t.rotation = float(std::numbers::pi / 2);
  t.scale = {2, 1};
  EXPECT_TRUE(near(glm::vec2(t.matrix() * glm::vec3(1, 0, 1)), {0, -2}));
  EXPECT_TRUE(near(glm::vec2(t.matrix() * glm::vec3(0, 1, 1)), {1, 0}));
}

// A file with the textures `textures` over three images: 0 a PNG, 1 a WebP, 2 a KTX2 (signatures only: the
// loader keeps the bytes, only the renderer decodes them), with `used` and `required` extensions.
Asset load_with_textures(const json& textures, const json& used, const json& required = json::array()) {
  json doc = {{"asset", {{"version", "2.0"}}},
              {"textures", textures},
              {"images", {{{"uri", "data:image/png;base64,iVBORw0KGgo="}},
                          // tinygltf decodes data URIs of a few mime types only; mimeType says which
                          {{"uri", "data:application/octet-stream;base64,UklGRgAAAABXRUJQ"}, {"mimeType", "image/webp"}},
                          {{"uri", "data:application/octet-stream;base64,q0tUWCAyMLsNChoK"}, {"mimeType", "image/ktx2"}}}}};
  if (!used.empty()) doc["extensionsUsed"] = used;
  if (!required.empty()) doc["extensionsRequired"] = required;
  const std::string text = doc.dump();
  return load_asset_from_memory(std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()), "test", ".");
}

TEST(TextureSource, WebpExtensionImageIsDrawnBeforeTheCoreFallback) {
  Asset asset = load_with_textures({{{"source", 0}, {"extensions", {{"EXT_texture_webp", {{"source", 1}}}}}}},
                                   {"EXT_texture_webp"});
  ASSERT_EQ(asset.textures.size(), 1u);
  EXPECT_EQ(asset.textures[0].image, 1) << "OpenImageIO decodes WebP: the fallback is for viewers that cannot";
  EXPECT_TRUE(asset.warnings.empty()) << all_warnings(asset);

  // Without a fallback the extension is required, and the file loads.
  asset = load_with_textures({{{"extensions", {{"EXT_texture_webp", {{"source", 1}}}}}}}, {"EXT_texture_webp"},
                             {"EXT_texture_webp"});
  EXPECT_EQ(asset.textures[0].image, 1);
  EXPECT_TRUE(asset.warnings.empty()) << all_warnings(asset);
}

TEST(TextureSource, WebpImageThatDoesNotExistFallsBackToTheCoreSource) {
  const Asset asset = load_with_textures({{{"source", 0}, {"extensions", {{"EXT_texture_webp", {{"source", 7}}}}}}},
                                         {"EXT_texture_webp"});
  EXPECT_EQ(asset.textures[0].image, 0);
  ASSERT_EQ(asset.warnings.size(), 1u) << all_warnings(asset);
  EXPECT_EQ(asset.warnings[0], "texture 0: EXT_texture_webp source 7 does not exist; its core source is used");
}

TEST(TextureSource, BasisuDrawsItsFallbackOrTheFactorsWithOneWarning) {
  Asset asset = load_with_textures({{{"source", 0}, {"extensions", {{"KHR_texture_basisu", {{"source", 2}}}}}}},
                                   {"KHR_texture_basisu"});
  EXPECT_EQ(asset.textures[0].image, 0) << "the PNG fallback";
  EXPECT_TRUE(asset.warnings.empty()) << all_warnings(asset);

  // Two textures with only a KTX2 image: one warning names both.
  const json only = {{"extensions", {{"KHR_texture_basisu", {{"source", 2}}}}}};
  asset = load_with_textures({only, {{"source", 0}}, only}, {"KHR_texture_basisu"}, {"KHR_texture_basisu"});
  EXPECT_EQ(asset.textures[0].image, -1);
  EXPECT_EQ(asset.textures[1].image, 0);
  EXPECT_EQ(asset.textures[2].image, -1);
  ASSERT_EQ(asset.warnings.size(), 1u) << all_warnings(asset);
  EXPECT_EQ(asset.warnings[0], "textures 0, 2 have only a KTX2 image (KHR_texture_basisu), which dqskin does not decode, "
                               "and no PNG or JPEG fallback; materials using them are drawn with their factors");
}

}  // namespace
}  // namespace dqskin
