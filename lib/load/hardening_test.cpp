// The loader against files made to attack it (docs/SECURITY.md): reading outside the model's folder, GLB
// headers whose sizes underflow, values the schema forbids, memory out of proportion to the file.
// The catalogue of malformed files (scripts/testdata/make_malformed.py) checks the messages through the command
// line; these tests check the parts one by one, under the sanitizers in the sanitize build.
#include "dqskin/error.hpp"
#include "dqskin/load.hpp"
#include "image_size.hpp"
#include "memory_estimate.hpp"
#include "model_io.hpp"
#include "precheck.hpp"
#include "resource_root.hpp"
#include "schema_values.hpp"
#include "../test_support/scratch_dir.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>

namespace dqskin::gltf {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

void put32(uint8_t* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = uint8_t(v >> (8 * i));
}

// Every GLB whose header's length or JSON chunk length is small (0 to 40), in files of 20 to 40 bytes, each
// in an allocation of exactly its size: json_chunk must refuse them without reading past the end (the
// sanitize build's AddressSanitizer would report a read; a length below 20 made `length - 20` wrap around).
TEST(GlbHeader, ShortLengthsAreRefusedWithoutReadingPastTheFile) {
  for (size_t size = 20; size <= 40; ++size)
    for (uint32_t length = 0; length <= 40; ++length)
      for (uint32_t json_length : {0u, 1u, 4u, 8u, 20u, 0xFFFFFFF0u}) {
        const std::unique_ptr<uint8_t[]> bytes(new uint8_t[size]);
        std::memset(bytes.get(), ' ', size);
        std::memcpy(bytes.get(), "glTF", 4);
        put32(bytes.get() + 4, 2);
        put32(bytes.get() + 8, length);
        put32(bytes.get() + 12, json_length);
        std::memcpy(bytes.get() + 16, "JSON", 4);
        try {
          const std::span<const uint8_t> chunk = json_chunk({bytes.get(), size}, true);
          EXPECT_GE(length, 20u) << "accepted a length below the headers";
          EXPECT_GE(chunk.data(), bytes.get() + 20);
          EXPECT_LE(chunk.data() + chunk.size(), bytes.get() + std::min<size_t>(size, length));
        } catch (const InputError&) {
        }
      }
}

TEST(ResourceRoot, PercentDecodingFollowsRfc3986) {
  EXPECT_EQ(percent_decode("a%20b%2Fc+d.png"), "a b/c+d.png");  // '+' is a plus, not a space, in a path
  EXPECT_EQ(percent_decode("%E2%82%AC.png"), "\xe2\x82\xac.png");
  EXPECT_THROW(percent_decode("a%2"), InputError);
  EXPECT_THROW(percent_decode("a%zz"), InputError);
  EXPECT_THROW(percent_decode("a%00.bin"), InputError);
}

class ResourceRootTest : public testing::Test {
protected:
  void SetUp() override {
    fs::create_directories(dir_ / "models" / "sub");
    fs::create_directories(dir_ / "textures");
    for (const fs::path& f : {dir_ / "models" / "a.bin", dir_ / "models" / "sub" / "b.bin", dir_ / "textures" / "t.png",
                              dir_ / "secret.bin"})
      std::ofstream(f) << "x";
    fs::create_symlink(dir_ / "secret.bin", dir_ / "models" / "link.bin");
    fs::create_symlink(dir_ / "models" / "a.bin", dir_ / "models" / "inside_link.bin");
    fs::create_directory_symlink(dir_ / "textures", dir_ / "models" / "textures_link");
  }
  const testing_support::ScratchDir scratch_{"resource_root"};
  const fs::path dir_ = scratch_.path();
  const std::string models_ = (dir_ / "models").string();
};

TEST_F(ResourceRootTest, FilesInsideTheModelsFolderAreRead) {
  const ResourceRoot root(models_, {});
  EXPECT_TRUE(root.check("a.bin", "buffer 0"));
  EXPECT_TRUE(root.check("sub/b.bin", "buffer 0"));
  EXPECT_TRUE(root.check("sub/../a.bin", "buffer 0"));
  EXPECT_TRUE(root.check("sub%2Fb.bin", "buffer 0"));
  EXPECT_TRUE(root.check("inside_link.bin", "buffer 0")) << "a link that stays inside is followed";
  EXPECT_FALSE(root.check("missing.bin", "buffer 0")) << "missing: the caller decides";
  EXPECT_TRUE(root.allows(models_ + "/a.bin"));
}

TEST_F(ResourceRootTest, EveryWayOutIsRefused) {
  const ResourceRoot root(models_, {});
  for (const char* uri : {"../secret.bin", "..%2Fsecret.bin", "%2E%2E/secret.bin", "sub/../../secret.bin", "link.bin",
                          "textures_link/t.png", "../missing.bin", "/etc/passwd", "file:///etc/passwd", "http://x/y.bin",
                          "sub", "."})
    EXPECT_THROW(root.check(uri, "buffer 0"), InputError) << uri;
  EXPECT_FALSE(root.allows((dir_ / "secret.bin").string()));
  EXPECT_FALSE(root.allows(models_ + "/link.bin"));
  EXPECT_FALSE(root.allows(models_ + "/sub")) << "a folder is not a file";
}

TEST_F(ResourceRootTest, AnExtraRootLetsASiblingFolderIn) {
  const ResourceRoot root(models_, {(dir_ / "textures").string()});
  EXPECT_TRUE(root.check("../textures/t.png", "image 0"));
  EXPECT_TRUE(root.check("textures_link/t.png", "image 0"));
  EXPECT_THROW(root.check("../secret.bin", "image 0"), InputError);
  EXPECT_THROW(ResourceRoot(models_, {(dir_ / "nowhere").string()}), InputError);
}

// A model at the top of the file system: tinygltf joins "/" and "etc/passwd" to "/etc/passwd".
TEST(ResourceRoot, AModelInTheRootFolderReadsBesideItself) {
  if (!fs::exists("/etc/passwd")) GTEST_SKIP() << "no /etc/passwd to stand for a file beside a model in /";
  const ResourceRoot root("/", {});
  EXPECT_TRUE(root.check("etc/passwd", "buffer 0"));
  EXPECT_TRUE(root.allows("/etc/passwd"));
  EXPECT_EQ(folder_of("/model.gltf"), "/");
  EXPECT_EQ(folder_of("model.gltf"), ".");
  EXPECT_EQ(folder_of("a/b/model.gltf"), "a/b");
}

TEST_F(ResourceRootTest, TheMessageNamesTheUriAndWhereItLeads) {
  try {
    ResourceRoot(models_, {}).check("link.bin", "image 3");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "image 3 uri 'link.bin' leads outside the model's folder (to " +
                                         (dir_ / "secret.bin").string() + "); dqskin does not read it");
  }
}

TEST(ScanJson, DepthIsCountedOutsideStringsOnly) {
  auto text = [](const std::string& s) { return std::span(reinterpret_cast<const uint8_t*>(s.data()), s.size()); };
  const std::string deep_ok = std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']');
  EXPECT_NO_THROW(scan_json(text(deep_ok)));
  const std::string too_deep = std::string(kMaxJsonDepth + 1, '[') + std::string(kMaxJsonDepth + 1, ']');
  EXPECT_THROW(scan_json(text(too_deep)), InputError);
  const std::string in_string = "{\"a\":\"" + std::string(10000, '[') + "\\\"[[,,\"}";
  const JsonShape shape = scan_json(text(in_string));
  EXPECT_EQ(shape.values, 1u);
  EXPECT_EQ(shape.objects, 1u);
  // Siblings do not add up: 1001 arrays side by side are one level, and 1001 values (empty arrays hold none).
  std::string wide = "[";
  for (int i = 0; i < 1000; ++i) wide += "[],";
  EXPECT_EQ(scan_json(text(wide + "[]]")).values, 1001u);
}

// Parsing a JSON text is refused before it starts when its shape says it would take more than the limit.
TEST(ScanJson, ATextOfMillionsOfValuesIsRefusedBeforeItIsParsed) {
  std::string text = "{\"asset\":{\"version\":\"2.0\"},\"nodes\":[{}";
  for (int i = 0; i < 200000; ++i) text += ",{}";
  text += "]}";
  LoadOptions options;
  options.max_memory = uint64_t(64) << 20;  // 200,001 objects are about 200 MB
  try {
    load_asset_from_memory(std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()), "nodes", ".", options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("its JSON (586 KiB, 200004 values) takes about", 0), 0u) << e.what();
  }
}

TEST(SchemaValues, AppearanceValuesAreRemovedWithAWarningOrderedByWhereTheyAre) {
  json doc = json::parse(R"({"asset":{"version":"2.0"},
    "samplers":[{"magFilter":1.5,"wrapS":33071},{"minFilter":-1}],
    "materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0,"texCoord":-2}},
                  "extras":{"fooTexture":{"index":-1}}}]})");
  const std::vector<std::string> warnings = check_schema_values(doc);
  ASSERT_EQ(warnings.size(), 3u);
  EXPECT_EQ(warnings[0], "material 0: pbrMetallicRoughness.baseColorTexture.texCoord -2 must be an index (an integer "
                         "from 0 to 2147483647); it is drawn without that texture");
  EXPECT_EQ(warnings[1], "sampler 0: magFilter 1.5 must be one of 9728, 9729; the default is used");
  EXPECT_EQ(warnings[2], "sampler 1: minFilter -1 must be one of 9728, 9729, 9984, 9985, 9986, 9987; the default is used");
  EXPECT_FALSE(doc["materials"][0]["pbrMetallicRoughness"].contains("baseColorTexture"));
  EXPECT_EQ(doc["samplers"][0], json::parse(R"({"wrapS":33071})"));
  EXPECT_EQ(doc["materials"][0]["extras"]["fooTexture"]["index"], -1) << "extras are the application's";
}

TEST(SchemaValues, StructuralValuesFailTheFile) {
  for (const char* text : {R"({"accessors":[{"byteOffset":-12}]})", R"({"accessors":[{"byteOffset":4.5}]})",
                           R"({"bufferViews":[{"byteStride":-12}]})", R"({"nodes":[{"mesh":4294967296}]})",
                           R"({"nodes":[{"children":[1.0]}]})", R"({"accessors":[{"normalized":1}]})"}) {
    json doc = json::parse(text);
    EXPECT_THROW(check_schema_values(doc), InputError) << text;
  }
}

// The estimate has to be in proportion to what loading really allocates: never less than the Asset's own
// arrays (else a file could pass the limit and still exhaust memory), and not so far above that real files
// are refused.
TEST(MemoryEstimate, IsInProportionToTheDecodedAsset) {
  const fs::path path = fs::path(DQSKIN_SHARED_TESTDATA_DIR) / "BrainStem" / "BrainStem.glb";
  if (!fs::exists(path)) GTEST_SKIP() << "shared test data not found: " << path;
  const Asset asset = load_asset(path.string());
  uint64_t decoded = 0;
  for (const Mesh& m : asset.meshes)
    for (const Primitive& p : m.primitives) {
      decoded += p.positions.size() * 12 + p.normals.size() * 12 + p.tangents.size() * 16 + p.uv0.size() * 8 +
                 p.uv1.size() * 8 + p.colors.size() * 16 + p.indices.size() * 4 + p.joints.size() * 2 + p.weights.size() * 4;
      for (const MorphTarget& t : p.targets) decoded += (t.positions.size() + t.normals.size() + t.tangents.size()) * 12;
    }
  for (const Clip& c : asset.clips)
    for (const Channel& ch : c.channels) decoded += (ch.times.size() + ch.values.size()) * 4;
  std::ifstream in(path, std::ios::binary);
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const ParsedModel parsed = parse_model(bytes, path.parent_path().string(), {});
  const MemoryEstimate estimate = estimate_memory(parsed.model);
  EXPECT_GE(estimate.asset, decoded);
  EXPECT_LE(estimate.asset, 3 * decoded);
  EXPECT_LE(estimate.total(), 4 * (decoded + bytes.size()));
}

// The sizes that headers declare, read for PNG, JPEG and WebP as OpenImageIO writes them, and every prefix
// of each file in an exactly sized allocation (nothing read past the end; a prefix gives the size or none).
TEST(DeclaredImageSize, ReadsPngJpegAndWebpHeadersWithinTheBytes) {
  const testing_support::ScratchDir scratch("image_size");
  for (const char* format : {"png", "jpg", "webp"}) {
    const fs::path path = scratch.path() / (std::string("image.") + format);
    const int width = 37, height = 21;
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(format);
    if (!out) GTEST_SKIP() << "OpenImageIO cannot write " << format;
    std::vector<uint8_t> pixels(size_t(width * height * 3), 128);
    ASSERT_TRUE(out->open(path.string(), OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::UINT8)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    ASSERT_TRUE(out->close());
    std::ifstream in(path, std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto size = declared_image_size(bytes);
    ASSERT_TRUE(size.has_value()) << format;
    EXPECT_EQ(size->first, uint32_t(width)) << format;
    EXPECT_EQ(size->second, uint32_t(height)) << format;
    for (size_t n = 0; n < std::min<size_t>(bytes.size(), 1024); ++n) {
      const std::unique_ptr<uint8_t[]> copy(new uint8_t[std::max<size_t>(n, 1)]);
      std::copy_n(bytes.begin(), n, copy.get());
      const auto prefix = declared_image_size({copy.get(), n});
      EXPECT_TRUE(!prefix || *prefix == *size) << format << " prefix " << n;
    }
  }
}

}  // namespace
}  // namespace dqskin::gltf
