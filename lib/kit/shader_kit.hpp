// The shader kits `dqskin bake --shader-kit` writes beside a bake (docs/formats.md, "Shader kits"): the
// reading shader of each layout for an engine, as files embedded in the library at build time (glsl/kits/
// and the player's own modules, web/*.js), so the binary alone writes them.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace dqskin::kit {

// One file of a kit: where it goes, relative to the bake's output folder, and its bytes.
struct KitFile {
  std::string path;  // shader_kit/<engine>/<name>
  std::string_view bytes;
};

// The engines every kit list may name, in the order they are written.
const std::vector<std::string>& kit_engines();

// "unity,unreal,godot,three" (any of them, comma-separated) or "all" → the engines, each once, in
// kit_engines() order; "" → none. Throws InputError naming an unknown or empty name.
std::vector<std::string> parse_shader_kits(const std::string& list);

// The files of those engines' kits, in a fixed order.
std::vector<KitFile> shader_kit_files(const std::vector<std::string>& engines);

}  // namespace dqskin::kit
