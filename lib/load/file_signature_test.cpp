// not_gltf_reason: what a file that is not glTF looks like, and no word for what is (or may be) glTF.
// is_gltf_file: a glTF file known by its bytes under any name.
#include "file_signature.hpp"

#include "dqskin/load.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string_view>

namespace dqskin::gltf {
namespace {

std::optional<std::string> reason(std::string_view text) {
  return not_gltf_reason({reinterpret_cast<const uint8_t*>(text.data()), text.size()});
}

TEST(FileSignature, GltfAndJsonObjectsAreLeftToTheParser) {
  EXPECT_FALSE(reason("glTF\x02\x00\x00\x00"));
  EXPECT_FALSE(reason("{\"asset\":{\"version\":\"2.0\"}}"));
  EXPECT_FALSE(reason("\xEF\xBB\xBF \r\n\t{}"));  // a byte order mark and whitespace first
  EXPECT_FALSE(reason(""));                       // empty and blank files: the parser says "empty"
  EXPECT_FALSE(reason(" \n"));
}

TEST(FileSignature, NamesTheFormatsUsersMeetInsteadOfGltf) {
  EXPECT_EQ(reason(std::string_view("PK\x03\x04\x14\x00", 6)), "is not a glTF file: it is a ZIP archive");
  EXPECT_EQ(reason("\x89PNG\r\n\x1A\nrest"), "is not a glTF file: it is a PNG image");
  EXPECT_EQ(reason("Kaydara FBX Binary  \x00"), "is not a glTF file: it is a binary FBX file");
}

TEST(FileSignature, QuotesTheFirstLineOfAnythingElsePrintably) {
  EXPECT_EQ(reason("<!DOCTYPE html>\n<html>"), "is not a glTF file: it starts with '<!DOCTYPE html>'");
  EXPECT_EQ(reason("[1, 2, 3]"), "is not a glTF file: it starts with '[1, 2, 3]'");
  EXPECT_EQ(reason("0123456789012345678901234567890"), "is not a glTF file: it starts with '012345678901234567890123'");
  const std::optional<std::string> escaped = reason("\x1B[31mred");
  ASSERT_TRUE(escaped);
  EXPECT_EQ(escaped->find('\x1B'), std::string::npos) << *escaped;  // no terminal escape reaches stderr
}

// A file of `bytes` named `name` in a fresh folder of the test's own.
std::string file_of(const std::string& name, std::string_view bytes) {
  const std::filesystem::path folder = std::filesystem::path(::testing::TempDir()) / "dqskin_is_gltf_file";
  std::filesystem::create_directories(folder);
  const std::string path = (folder / name).string();
  std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  return path;
}

TEST(IsGltfFile, KnowsAGltfFileByItsBytesUnderAnyName) {
  EXPECT_TRUE(is_gltf_file(file_of("avatar.vrm", std::string_view("glTF\x02\x00\x00\x00", 8))));
  EXPECT_TRUE(is_gltf_file(file_of("model", std::string_view("glTF\x02\x00\x00\x00", 8))));
  EXPECT_TRUE(is_gltf_file(file_of("model.dat", "\xEF\xBB\xBF\n  {\"asset\": {\"version\": \"2.0\"}}")));
}

TEST(IsGltfFile, ImagesFoldersAndMissingFilesAreNot) {
  EXPECT_FALSE(is_gltf_file(file_of("frame.png", "\x89PNG\r\n\x1A\nrest")));
  EXPECT_FALSE(is_gltf_file(file_of("notes.txt", "glt")));
  EXPECT_FALSE(is_gltf_file(file_of("empty.bin", "")));
  EXPECT_FALSE(is_gltf_file(std::filesystem::path(file_of("x.bin", "")).parent_path().string()));
  EXPECT_FALSE(is_gltf_file(file_of("x.bin", "").append(".missing")));
}

TEST(IsGltfFile, AGltfNameIsGltfWhateverItHoldsSoTheLoaderSaysWhatItIs) {
  EXPECT_TRUE(is_gltf_file(file_of("page.GLB", "<!DOCTYPE html>")));
  EXPECT_TRUE(is_gltf_file(file_of("missing.gltf", "").append(".gltf")));
}

}  // namespace
}  // namespace dqskin::gltf
