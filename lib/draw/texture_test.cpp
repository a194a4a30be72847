// Materials in the renderer: glTF images decoded from memory (PNG and JPEG, every PNG color type, errors
// named), and drawn as glTF says: UV (0, 0) at the image's top-left, sRGB texels decoded to linear,
// base color = factor × texture × COLOR_0, alpha MASK cuts out and BLEND blends, KHR_texture_transform
// moves the UVs. Tests that need an OpenGL context skip with the reason when the machine has none.
#include "texture_image.hpp"

#include "dqskin/camera.hpp"
#include "dqskin/deformer.hpp"
#include "dqskin/error.hpp"
#include "dqskin/image_output.hpp"
#include "dqskin/load.hpp"
#include "dqskin/renderer.hpp"
#include "dqskin/skinning.hpp"
#include "../test_support/gpu_context.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

namespace dqskin {
namespace {

// `pixels` (top row first, `channels` per pixel, of `type`) encoded in memory as `format` (png or jpg).
EncodedImage encode(const char* format, int width, int height, int channels, OIIO::TypeDesc type, const void* pixels) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput out(bytes);
  std::unique_ptr<OIIO::ImageOutput> writer = OIIO::ImageOutput::create(format);
  EXPECT_TRUE(writer);
  OIIO::ImageSpec spec(width, height, channels, type);
  if (channels == 2 || channels == 4) spec.attribute("oiio:UnassociatedAlpha", 1);
  writer->set_ioproxy(&out);
  EXPECT_TRUE(writer->open(std::string("memory.") + format, spec)) << writer->geterror();
  EXPECT_TRUE(writer->write_image(type, pixels)) << writer->geterror();
  writer->close();
  EncodedImage image;
  image.name = "test";
  image.bytes.assign(bytes.begin(), bytes.end());
  return image;
}

TEST(TextureImage, EveryPngColorTypeBecomesStraightRgba) {
  const uint8_t grey[] = {10, 200};
  Image8 d = decode_texture_image(encode("png", 2, 1, 1, OIIO::TypeDesc::UINT8, grey), 0, 64);
  EXPECT_EQ(d.rgba, (std::vector<uint8_t>{10, 10, 10, 255, 200, 200, 200, 255}));

  const uint8_t grey_alpha[] = {10, 0, 200, 128};  // alpha 0 with a colour: must stay unpremultiplied
  d = decode_texture_image(encode("png", 2, 1, 2, OIIO::TypeDesc::UINT8, grey_alpha), 0, 64);
  EXPECT_EQ(d.rgba, (std::vector<uint8_t>{10, 10, 10, 0, 200, 200, 200, 128}));

  const uint8_t rgb[] = {1, 2, 3, 4, 5, 6};
  d = decode_texture_image(encode("png", 1, 2, 3, OIIO::TypeDesc::UINT8, rgb), 0, 64);
  EXPECT_EQ(d.width, 1);
  EXPECT_EQ(d.height, 2);
  EXPECT_EQ(d.rgba, (std::vector<uint8_t>{1, 2, 3, 255, 4, 5, 6, 255})) << "top row first";

  const uint16_t rgba16[] = {65535, 0, 32896, 0};  // 32896 = 128.5 × 257 → 128 or 129 after rounding
  d = decode_texture_image(encode("png", 1, 1, 4, OIIO::TypeDesc::UINT16, rgba16), 0, 64);
  EXPECT_EQ(d.rgba[0], 255);
  EXPECT_EQ(d.rgba[1], 0);
  EXPECT_NEAR(d.rgba[2], 128, 1);
  EXPECT_EQ(d.rgba[3], 0);
}

TEST(TextureImage, JpegDecodesNearItsColors) {
  std::vector<uint8_t> rgb(16 * 16 * 3);
  for (size_t i = 0; i < rgb.size(); i += 3) rgb[i] = 200, rgb[i + 1] = 100, rgb[i + 2] = 50;
  const Image8 d = decode_texture_image(encode("jpg", 16, 16, 3, OIIO::TypeDesc::UINT8, rgb.data()), 0, 64);
  ASSERT_EQ(d.rgba.size(), 16u * 16u * 4u);
  EXPECT_NEAR(d.rgba[0], 200, 4);  // lossy
  EXPECT_NEAR(d.rgba[1], 100, 4);
  EXPECT_NEAR(d.rgba[2], 50, 4);
  EXPECT_EQ(d.rgba[3], 255);
}

void expect_error(const EncodedImage& image, int max_side, const std::string& expected) {
  try {
    decode_texture_image(image, 3, max_side);
    ADD_FAILURE() << "expected InputError: " << expected;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line";
  }
}

TEST(TextureImage, BadImagesAreNamedErrors) {
  EncodedImage missing;
  missing.uri = "textures/skin.png";
  expect_error(missing, 64, "image 3 (textures/skin.png): has no data");

  EncodedImage text;
  text.name = "notes";
  text.bytes = {'h', 'e', 'l', 'l', 'o'};
  expect_error(text, 64, "image 3 'notes': is neither PNG nor JPEG");

  const uint8_t rgb[] = {1, 2, 3, 4, 5, 6};
  EncodedImage truncated = encode("png", 1, 2, 3, OIIO::TypeDesc::UINT8, rgb);
  truncated.bytes.resize(truncated.bytes.size() / 2);
  expect_error(truncated, 64, "image 3 'test': cannot be decoded");

  const std::vector<uint8_t> wide(65 * 3);
  expect_error(encode("png", 65, 1, 3, OIIO::TypeDesc::UINT8, wide.data()), 64,
               "image 3 'test': is 65x1 pixels; this GPU takes textures of 1 to 64 a side");

  // A PNG whose header claims 10000x9000 pixels (90 M) but has no pixel data: refused from the header,
  // before 360 MB are allocated.
  const uint8_t tiny[] = {1, 2, 3};
  EncodedImage claims = encode("png", 1, 1, 3, OIIO::TypeDesc::UINT8, tiny);
  const uint8_t ihdr_size[] = {0, 0, 0x27, 0x10, 0, 0, 0x23, 0x28};  // 10000, 9000 big-endian
  std::copy(std::begin(ihdr_size), std::end(ihdr_size), claims.bytes.begin() + 16);
  uint32_t crc = 0xffffffffu;  // PNG's CRC-32 over the chunk type and data (bytes 12 to 28), so it still parses
  for (size_t i = 12; i < 29; ++i) {
    crc ^= claims.bytes[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  crc = ~crc;
  for (size_t i = 0; i < 4; ++i) claims.bytes[29 + i] = uint8_t(crc >> (24 - 8 * i));
  expect_error(claims, 16384, "is 10000x9000 pixels, more than dqskin draws");
}

// ---------------------------------------------------------------------------------------------------
// Drawing: a square facing the camera, filling an orthographic view exactly.

using testing_support::context_or_null;

// A square [−1, 1]² at z = 0 facing +z, two triangles, UV (0, 0) at its top-left corner (−1, 1), with
// `material` and the given COLOR_0 (or none). Drawn by node 0.
Asset square(const Material& material, std::vector<glm::vec4> colors = {}) {
  Asset asset;
  Primitive p;
  p.positions = {{-1, 1, 0}, {1, 1, 0}, {1, -1, 0}, {-1, -1, 0}};
  p.normals.assign(4, glm::vec3(0, 0, 1));
  p.uv0 = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  p.colors = std::move(colors);
  p.indices = {0, 3, 2, 0, 2, 1};
  p.material = 0;
  asset.meshes.push_back({"square", {p}, {}});
  Node node;
  node.mesh = 0;
  asset.nodes.push_back(node);
  asset.materials.push_back(material);
  return asset;
}

// An RGBA8 PNG of 2x2 texels as a texture of the asset, sampled NEAREST and clamped.
void add_texture(Asset& asset, const std::array<uint8_t, 16>& texels) {
  asset.images.push_back(encode("png", 2, 2, 4, OIIO::TypeDesc::UINT8, texels.data()));
  Texture texture;
  texture.image = 0;
  texture.sampler = {9728, 9728, 33071, 33071};
  asset.textures.push_back(texture);
  asset.materials[0].base_color_texture.texture = 0;
}

// The square rendered 64x64 on `background` through an orthographic camera at z = 5 that sees exactly it.
Image draw(GpuContext& context, const Asset& asset, glm::vec4 background = {0, 0, 0, 1}) {
  RendererOptions options;
  options.width = options.height = 64;
  options.samples = 1;
  options.background = background;
  const std::vector<MeshInstance> instances = {{0, 0, -1}};
  Renderer renderer(context, asset, instances, options);
  const Primitive& p = asset.meshes[0].primitives[0];
  FrameView frame;
  frame.primitives.push_back({4, {&p.positions[0].x, 12}, {&p.normals[0].x, 12}, {}});
  SceneCamera ortho;
  ortho.orthographic = true;
  ortho.xmag = ortho.ymag = 1;
  ortho.znear = 1;
  ortho.zfar = 10;
  Mat4<double> world(1.0);
  world[3] = {0, 0, 5, 1};
  return renderer.render(frame, scene_camera(ortho, world, 1.0));
}

glm::vec4 pixel(const Image& image, int x, int y) {
  const size_t i = (size_t(y) * size_t(image.width) + size_t(x)) * 4;
  return {image.rgba[i], image.rgba[i + 1], image.rgba[i + 2], image.rgba[i + 3]};
}

TEST(RenderMaterials, TextureTopLeftTexelIsTheSquaresTopLeftAndSrgbIsDecoded) {
  const std::unique_ptr<GpuContext> context = context_or_null();
  if (!context) GTEST_SKIP() << "no OpenGL context on this machine";
  Asset asset = square(Material{});
  // Top-left red, top-right green, bottom-left blue, bottom-right grey at sRGB 128.
  add_texture(asset, {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 128, 128, 128, 255});
  const Image image = draw(*context, asset);
  const glm::vec4 tl = pixel(image, 16, 16), tr = pixel(image, 48, 16), bl = pixel(image, 16, 48), br = pixel(image, 48, 48);
  EXPECT_GT(tl.r, 0.3f);
  EXPECT_LT(tl.g + tl.b, 0.01f);
  EXPECT_GT(tr.g, 0.3f);
  EXPECT_LT(tr.r + tr.b, 0.01f);
  EXPECT_GT(bl.b, 0.3f);
  EXPECT_LT(bl.r + bl.g, 0.01f);
  // sRGB 128 is linear 0.2158 of white; the lighting is the same at the two points within the fill
  // light's small change across the view.
  const glm::vec4 white_ref = pixel(image, 47, 16);  // green texel, same row: compare against its light
  EXPECT_NEAR(br.r / white_ref.g, 0.2158f, 0.01f) << "texels are sRGB-decoded before lighting";
}

TEST(RenderMaterials, FactorTextureAndVertexColorMultiply) {
  const std::unique_ptr<GpuContext> context = context_or_null();
  if (!context) GTEST_SKIP() << "no OpenGL context on this machine";
  Material plain;
  const Image reference = draw(*context, square(plain));  // white: the light alone
  Material tinted;
  tinted.base_color = {0.5f, 1.0f, 0.25f, 1.0f};
  Asset asset = square(tinted, std::vector<glm::vec4>(4, glm::vec4(1.0f, 0.5f, 1.0f, 1.0f)));
  add_texture(asset, {255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255});
  const Image image = draw(*context, asset);
  for (const auto& [x, y] : {std::pair{10, 10}, std::pair{40, 50}}) {
    const glm::vec4 light = pixel(reference, x, y), c = pixel(image, x, y);
    EXPECT_NEAR(c.r / light.r, 0.5f, 2e-3f);
    EXPECT_NEAR(c.g / light.g, 0.5f, 2e-3f);
    EXPECT_NEAR(c.b / light.b, 0.25f, 2e-3f);
  }
}

TEST(RenderMaterials, MaskCutsOutAndBlendMixesWithTheBackground) {
  const std::unique_ptr<GpuContext> context = context_or_null();
  if (!context) GTEST_SKIP() << "no OpenGL context on this machine";
  const glm::vec4 background(0.0f, 0.0f, 1.0f, 1.0f);
  // Left column alpha 0.2 (51), right column alpha 0.8 (204); white texels.
  const std::array<uint8_t, 16> texels = {255, 255, 255, 51, 255, 255, 255, 204, 255, 255, 255, 51, 255, 255, 255, 204};
  Material mask;
  mask.alpha_mode = AlphaMode::kMask;
  mask.alpha_cutoff = 0.5f;
  Asset masked = square(mask);
  add_texture(masked, texels);
  const Image cut = draw(*context, masked, background);
  EXPECT_EQ(pixel(cut, 16, 32), background) << "alpha 0.2 < cutoff 0.5: not drawn";
  EXPECT_GT(pixel(cut, 48, 32).r, 0.3f) << "alpha 0.8: drawn, opaque";

  Material blend;
  blend.alpha_mode = AlphaMode::kBlend;
  Asset blended = square(blend);
  add_texture(blended, texels);
  const Image mixed = draw(*context, blended, background);
  const Image opaque = draw(*context, square(Material{}), background);
  for (const auto& [x, alpha] : {std::pair{16, 0.2f}, std::pair{48, 0.8f}}) {
    const glm::vec4 c = pixel(mixed, x, 32), lit = pixel(opaque, x, 32);
    EXPECT_NEAR(c.r, alpha * lit.r, 2e-3f);
    EXPECT_NEAR(c.b, alpha * lit.b + (1 - alpha) * background.b, 2e-3f);
  }

  Material opaque_material;  // OPAQUE ignores the texture's alpha
  Asset ignored = square(opaque_material);
  add_texture(ignored, texels);
  EXPECT_NEAR(pixel(draw(*context, ignored, background), 16, 32).b, pixel(opaque, 16, 32).b, 1e-3f);
}

TEST(RenderMaterials, UndecodableTextureIsAnInputErrorNamingTheImage) {
  const std::unique_ptr<GpuContext> context = context_or_null();
  if (!context) GTEST_SKIP() << "no OpenGL context on this machine";
  Asset asset = square(Material{});
  add_texture(asset, {});
  asset.images[0].bytes.resize(10);
  asset.images[0].name = "broken";
  try {
    draw(*context, asset);
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("image 0 'broken': cannot be decoded"), std::string::npos) << e.what();
  }
  // Shades that do not show materials do not decode textures, so the same asset draws.
  RendererOptions normals;
  normals.shade = Shade::kNormals;
  EXPECT_NO_THROW(Renderer(*context, asset, {{0, 0, -1}}, normals));
}

// ---------------------------------------------------------------------------------------------------
// KHR_texture_transform: uv' = T · R · S · uv, applied to the UVs the base color texture is read with.

// A 4x4 RGBA8 texture, NEAREST and clamped: its lower-left quadrant red, green (top row), blue, yellow
// (bottom row); the rest white.
void add_quadrant_texture(Asset& asset) {
  std::vector<uint8_t> texels(4 * 4 * 4, 255);
  auto set = [&](int x, int y, uint8_t r, uint8_t g, uint8_t b) {
    uint8_t* t = &texels[size_t(y * 4 + x) * 4];
    t[0] = r, t[1] = g, t[2] = b;
  };
  set(0, 2, 255, 0, 0);
  set(1, 2, 0, 255, 0);
  set(0, 3, 0, 0, 255);
  set(1, 3, 255, 255, 0);
  asset.images.push_back(encode("png", 4, 4, 4, OIIO::TypeDesc::UINT8, texels.data()));
  Texture texture;
  texture.image = 0;
  texture.sampler = {9728, 9728, 33071, 33071};
  asset.textures.push_back(texture);
  asset.materials[0].base_color_texture.texture = 0;
}

enum class Hue { kRed, kGreen, kBlue, kYellow, kWhite, kOther };
Hue hue(glm::vec4 c) {
  const float m = std::max({c.r, c.g, c.b});
  auto on = [&](float x) { return x > 0.5f * m; };
  if (m < 0.05f) return Hue::kOther;
  if (on(c.r) && on(c.g) && on(c.b)) return Hue::kWhite;
  if (on(c.r) && on(c.g)) return Hue::kYellow;
  if (on(c.r) && !on(c.b)) return Hue::kRed;
  if (on(c.g) && !on(c.r) && !on(c.b)) return Hue::kGreen;
  if (on(c.b) && !on(c.r) && !on(c.g)) return Hue::kBlue;
  return Hue::kOther;
}

// The extension's own example: offset (0, 1), rotation 90°, scale 0.5 "utilizes only the lower left
// quadrant of the source image, rotated clockwise 90°". The quadrant [[red, green], [blue, yellow]] turned
// clockwise is [[blue, red], [yellow, green]] on the square. With the rotation's sign flipped (the GLSL
// listing of the extension's README read literally) the UVs leave the image and the clamp shows blue
// everywhere; without the transform the square's corners show white.
TEST(RenderTextureTransform, RotationTurnsTheImageClockwiseAsTheExtensionsExampleSays) {
  const std::unique_ptr<GpuContext> context = context_or_null();
  if (!context) GTEST_SKIP() << "no OpenGL context on this machine";
  Asset asset = square(Material{});
  add_quadrant_texture(asset);
  TextureTransform& t = asset.materials[0].base_color_texture.transform;
  t.offset = {0.0f, 1.0f};
  t.rotation = 1.57079632679f;
  t.scale = {0.5f, 0.5f};
  const Image image = draw(*context, asset);
  EXPECT_EQ(hue(pixel(image, 16, 16)), Hue::kBlue) << "top-left";
  EXPECT_EQ(hue(pixel(image, 48, 16)), Hue::kRed) << "top-right";
  EXPECT_EQ(hue(pixel(image, 16, 48)), Hue::kYellow) << "bottom-left";
  EXPECT_EQ(hue(pixel(image, 48, 48)), Hue::kGreen) << "bottom-right";

  // The same through TEXCOORD_1 (KHR_texture_transform's texCoord override, resolved by the loader),
  // with TEXCOORD_0 mirrored so that reading the wrong set shows.
  Primitive& p = asset.meshes[0].primitives[0];
  p.uv1 = p.uv0;
  for (glm::vec2& uv : p.uv0) uv.x = 1 - uv.x;
  asset.materials[0].base_color_texture.texcoord = 1;
  const Image second = draw(*context, asset);
  EXPECT_EQ(0, std::memcmp(image.rgba.data(), second.rgba.data(), image.rgba.size() * sizeof(float)));
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The asset's first clip at `time`, deformed on the GPU, drawn 256x256 with the automatic camera.
Image render_at(GpuContext& context, const Asset& asset, double time) {
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  DeformerOptions deformer_options;
  deformer_options.backend = testing_support::backend_of(context);
  const std::unique_ptr<Deformer> deformer = make_deformer(&context, asset, instances, deformer_options);
  std::vector<DeformedBatch> batches;
  const std::vector<double> times = {time};
  deformer->run(&asset.clips.at(0), times, [&](const DeformedBatch& b) { batches.push_back(b); });
  const FrameView frame = frame_view(batches.at(0), 0);
  Bounds box;
  box.add(frame);
  RendererOptions options;
  options.width = options.height = 256;
  Renderer renderer(context, asset, instances, options);
  return renderer.render(frame, frame_camera(box, {}, 1.0));
}

struct ImageDifference {
  float largest = 0;       // largest channel difference
  double over_2_255 = 0;   // share of pixels with a channel more than 2/255 apart
};
ImageDifference difference(const Image& a, const Image& b) {
  ImageDifference d;
  size_t over = 0;
  for (size_t p = 0; p < a.rgba.size() / 4; ++p) {
    float worst = 0;
    for (size_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(a.rgba[p * 4 + c] - b.rgba[p * 4 + c]));
    d.largest = std::max(d.largest, worst);
    over += worst > 2.0f / 255.0f ? 1 : 0;
  }
  d.over_2_255 = double(over) / double(a.rgba.size() / 4);
  return d;
}

// The textured cylinder with a transform of offset, rotation and non-uniform scale in its file renders as
// the same file whose TEXCOORD_0 was transformed on the CPU (uv' = T · R · S · uv) and has no extension.
// The two differ only by float rounding (in the shader or here), which moves a few texel edges of the
// NEAREST-magnified checker by a pixel: at most 0.5 % of the pixels differ by more than 2/255. The same
// with the rotation's sign flipped differs on a large share of the pixels, so the comparison would catch it.
TEST(RenderTextureTransform, TransformInTheFileEqualsUvsTransformedOnTheCpu) {
  const std::unique_ptr<GpuContext> context = context_or_null();
  if (!context) GTEST_SKIP() << "no OpenGL context on this machine";
  const std::string dir = DQSKIN_TESTDATA_DIR;
  const std::string path = dir + "/textured_cylinder.gltf";
  const glm::vec2 offset(0.2f, 0.3f), scale(1.5f, 0.7f);
  const float rotation = 0.3f;

  nlohmann::json doc = nlohmann::json::parse(read_text(path));
  doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"] = {
      {"offset", {offset.x, offset.y}}, {"rotation", rotation}, {"scale", {scale.x, scale.y}}};
  doc["extensionsUsed"] = {"KHR_texture_transform"};
  const std::string text = doc.dump();
  const Asset in_file = load_asset_from_memory(std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()),
                                               "textured_cylinder+KHR_texture_transform", dir);
  ASSERT_TRUE(in_file.warnings.empty()) << in_file.warnings[0];
  ASSERT_EQ(in_file.materials[0].base_color_texture.transform.rotation, rotation);

  // uv' = T · R · S · uv, written out: R turns (1, 0) towards -v, counter-clockwise as seen on the image.
  auto on_cpu = [&](float sign) {
    Asset asset = load_asset(path);
    const double c = std::cos(double(rotation)), s = double(sign) * std::sin(double(rotation));
    for (glm::vec2& uv : asset.meshes.at(0).primitives.at(0).uv0) {
      const double u = double(scale.x) * double(uv.x), v = double(scale.y) * double(uv.y);
      uv = glm::vec2(float(c * u + s * v + double(offset.x)), float(-s * u + c * v + double(offset.y)));
    }
    return asset;
  };
  const Image a = render_at(*context, in_file, 0.5);
  const Image b = render_at(*context, on_cpu(1.0f), 0.5);
  const ImageDifference same = difference(a, b);
  std::printf("transform in the file vs UVs transformed on the CPU: largest channel difference %g, %.3f %% of "
              "pixels differ by more than 2/255\n", double(same.largest), 100 * same.over_2_255);
  EXPECT_LE(same.over_2_255, 0.005);

  const ImageDifference flipped = difference(a, render_at(*context, on_cpu(-1.0f), 0.5));
  std::printf("... vs the rotation's sign flipped: %.1f %% of pixels differ by more than 2/255\n",
              100 * flipped.over_2_255);
  EXPECT_GE(flipped.over_2_255, 0.05);
  const ImageDifference untransformed = difference(a, render_at(*context, load_asset(path), 0.5));
  EXPECT_GE(untransformed.over_2_255, 0.05);
}

}  // namespace
}  // namespace dqskin
