// The shader kits' names and files (lib/kit/shader_kit.hpp): the list `--shader-kit` takes, and that each
// file written is its source, byte for byte. That every file compiles is kits.compile (glsl/kits/check_kits.py).
#include "shader_kit.hpp"

#include "dqskin/error.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace dqskin::kit {
namespace {

std::string read_source(const std::string& relative) {
  std::ifstream in(std::string(DQSKIN_TESTDATA_DIR) + "/../" + relative, std::ios::binary);
  EXPECT_TRUE(in) << relative;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ShaderKit, ParsesTheEngineList) {
  EXPECT_TRUE(parse_shader_kits("").empty());
  EXPECT_EQ(parse_shader_kits("all"), kit_engines());
  EXPECT_EQ(parse_shader_kits("three,unity,three"), (std::vector<std::string>{"unity", "three"}));
  EXPECT_EQ(parse_shader_kits("godot,all"), kit_engines());
  EXPECT_THROW(parse_shader_kits("unity,vulkan"), InputError);
  EXPECT_THROW(parse_shader_kits("unity,"), InputError);
  EXPECT_THROW(parse_shader_kits("Unity"), InputError);
  try {
    parse_shader_kits("vulkan");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--shader-kit 'vulkan' is not one of unity, unreal, godot, three, all");
  }
}

TEST(ShaderKit, EachFileIsItsSourceByteForByte) {
  const std::map<std::string, std::string> sources = {
      {"shader_kit/unity/Dqskin.hlsl", "glsl/kits/hlsl/dqskin.hlsl"},
      {"shader_kit/unity/DqskinShaderGraph.hlsl", "glsl/kits/unity/DqskinShaderGraph.hlsl"},
      {"shader_kit/unreal/Dqskin.ush", "glsl/kits/hlsl/dqskin.hlsl"},
      {"shader_kit/godot/dqskin.gdshaderinc", "glsl/kits/godot/dqskin.gdshaderinc"},
      {"shader_kit/godot/dqskin_vat.gdshader", "glsl/kits/godot/dqskin_vat.gdshader"},
      {"shader_kit/godot/dqskin_bones.gdshader", "glsl/kits/godot/dqskin_bones.gdshader"},
      {"shader_kit/three/vat_material.js", "web/vat_material.js"},
      {"shader_kit/three/bones_material.js", "web/bones_material.js"},
      {"shader_kit/three/shading.js", "web/shading.js"},
  };
  const std::vector<KitFile> files = shader_kit_files(kit_engines());
  ASSERT_EQ(files.size(), sources.size());
  for (const KitFile& file : files) {
    ASSERT_TRUE(sources.count(file.path)) << file.path;
    EXPECT_EQ(std::string(file.bytes), read_source(sources.at(file.path))) << file.path;
  }
}

TEST(ShaderKit, WritesOnlyTheEnginesAsked) {
  const std::vector<KitFile> files = shader_kit_files({"godot"});
  ASSERT_EQ(files.size(), 3u);
  for (const KitFile& file : files) EXPECT_EQ(file.path.rfind("shader_kit/godot/", 0), 0u) << file.path;
  EXPECT_TRUE(shader_kit_files({}).empty());
}

}  // namespace
}  // namespace dqskin::kit
