// The shader kits as files (lib/kit/shader_kit.hpp). Their texts are compiled in from glsl/kits/ and web/
// (lib/CMakeLists.txt, glsl/kits/embed_kit.cmake); the three.js kit is the player's modules byte for byte.
#include "shader_kit.hpp"

#include "dqskin/error.hpp"

#include <algorithm>

namespace dqskin::kit {

// Generated at build time, one per source file (glsl/kits/embed_kit.cmake).
extern const std::string_view kKitHlslCore, kKitUnityShaderGraph, kKitGodotInclude, kKitGodotVat, kKitGodotBones,
    kKitThreeVat, kKitThreeBones, kKitThreeShading;

namespace {

struct Entry {
  const char* engine;
  const char* name;
  const std::string_view* bytes;
};

// One HLSL core serves Unity (included by the Shader Graph entry points) and Unreal (a .ush for a Custom
// node's include paths): the same text under each engine's name.
const Entry kFiles[] = {
    {"unity", "Dqskin.hlsl", &kKitHlslCore},
    {"unity", "DqskinShaderGraph.hlsl", &kKitUnityShaderGraph},
    {"unreal", "Dqskin.ush", &kKitHlslCore},
    {"godot", "dqskin.gdshaderinc", &kKitGodotInclude},
    {"godot", "dqskin_vat.gdshader", &kKitGodotVat},
    {"godot", "dqskin_bones.gdshader", &kKitGodotBones},
    {"three", "vat_material.js", &kKitThreeVat},
    {"three", "bones_material.js", &kKitThreeBones},
    {"three", "shading.js", &kKitThreeShading},
};

}  // namespace

const std::vector<std::string>& kit_engines() {
  static const std::vector<std::string> engines = {"unity", "unreal", "godot", "three"};
  return engines;
}

std::vector<std::string> parse_shader_kits(const std::string& list) {
  std::vector<bool> wanted(kit_engines().size(), false);
  size_t start = 0;
  while (start <= list.size() && !list.empty()) {
    const size_t comma = std::min(list.find(',', start), list.size());
    const std::string name = list.substr(start, comma - start);
    if (name == "all") {
      std::fill(wanted.begin(), wanted.end(), true);
    } else {
      const auto it = std::find(kit_engines().begin(), kit_engines().end(), name);
      if (it == kit_engines().end())
        throw InputError("--shader-kit '" + name + "' is not one of unity, unreal, godot, three, all");
      wanted[size_t(it - kit_engines().begin())] = true;
    }
    start = comma + 1;
  }
  std::vector<std::string> engines;
  for (size_t i = 0; i < wanted.size(); ++i)
    if (wanted[i]) engines.push_back(kit_engines()[i]);
  return engines;
}

std::vector<KitFile> shader_kit_files(const std::vector<std::string>& engines) {
  std::vector<KitFile> files;
  for (const std::string& engine : kit_engines()) {
    if (std::find(engines.begin(), engines.end(), engine) == engines.end()) continue;
    for (const Entry& e : kFiles)
      if (engine == e.engine) files.push_back({"shader_kit/" + engine + "/" + e.name, *e.bytes});
  }
  return files;
}

}  // namespace dqskin::kit
