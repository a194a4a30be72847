#include "schema_values.hpp"

#include "dqskin/error.hpp"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace dqskin::gltf {
namespace {

using nlohmann::json;

// What a value must be: an integer in [min, max], a multiple of `step`, and one of `allowed` when given;
// or, with `boolean`, true or false.
struct Constraint {
  int64_t min = 0, max = INT_MAX;  // tinygltf reads indices into int
  int64_t step = 1;
  std::initializer_list<int64_t> allowed = {};
  bool boolean = false;
};

constexpr Constraint kIndex{};                      // glTFid (§5: "integer, minimum 0")
constexpr Constraint kOffset{0, INT64_MAX};         // byteOffset
constexpr Constraint kCount{1, INT64_MAX};          // count, byteLength
constexpr Constraint kMode{0, 6};                   // primitive.mode (§5.24.4)
constexpr Constraint kStride{4, 252, 4};            // bufferView.byteStride (§5.11.4)
constexpr Constraint kBoolean{0, 0, 1, {}, true};   // tinygltf reads anything else as false

// One rule: the values at `path` and what they must be. Path segments: a member name; "*" any array
// element or object member; "*Texture" any member whose name ends in "Texture" (every textureInfo of
// the core and the KHR_materials_* schemas); "**" any number of levels, never into "extras" (the
// application's own data).
struct Rule {
  const char* path;
  Constraint constraint;
  // Appearance rules only (else nullptr: a bad value fails the input): what the warning says happens.
  const char* consequence = nullptr;
  int drop_levels = 0;  // what is removed with a bad value: 0 the value, 1 the object holding it, …
};

const Rule kRules[] = {
    {"scene", kIndex},
    {"scenes/*/nodes/*", kIndex},
    {"nodes/*/children/*", kIndex},
    {"nodes/*/mesh", kIndex},
    {"nodes/*/skin", kIndex},
    {"meshes/*/primitives/*/attributes/*", kIndex},
    {"meshes/*/primitives/*/indices", kIndex},
    {"meshes/*/primitives/*/mode", kMode},
    {"meshes/*/primitives/*/targets/*/*", kIndex},
    {"skins/*/inverseBindMatrices", kIndex},
    {"skins/*/skeleton", kIndex},
    {"skins/*/joints/*", kIndex},
    {"animations/*/channels/*/sampler", kIndex},
    {"animations/*/channels/*/target/node", kIndex},
    {"animations/*/samplers/*/input", kIndex},
    {"animations/*/samplers/*/output", kIndex},
    {"accessors/*/bufferView", kIndex},
    {"accessors/*/byteOffset", kOffset},
    {"accessors/*/componentType", {0, INT_MAX, 1, {5120, 5121, 5122, 5123, 5125, 5126}}},
    {"accessors/*/count", kCount},
    {"accessors/*/normalized", kBoolean},
    {"accessors/*/sparse/count", kCount},
    {"accessors/*/sparse/indices/bufferView", kIndex},
    {"accessors/*/sparse/indices/byteOffset", kOffset},
    {"accessors/*/sparse/indices/componentType", {0, INT_MAX, 1, {5121, 5123, 5125}}},
    {"accessors/*/sparse/values/bufferView", kIndex},
    {"accessors/*/sparse/values/byteOffset", kOffset},
    {"bufferViews/*/buffer", kIndex},
    {"bufferViews/*/byteOffset", kOffset},
    {"bufferViews/*/byteLength", kCount},
    {"bufferViews/*/byteStride", kStride},
    {"bufferViews/*/target", {0, INT_MAX, 1, {34962, 34963}}},
    {"buffers/*/byteLength", kCount},
    {"images/*/bufferView", kIndex},
    // EXT_meshopt_compression: the compressed range and its layout (meshopt.hpp checks how they fit).
    {"bufferViews/*/extensions/EXT_meshopt_compression/buffer", kIndex},
    {"bufferViews/*/extensions/EXT_meshopt_compression/byteOffset", kOffset},
    {"bufferViews/*/extensions/EXT_meshopt_compression/byteLength", kCount},
    {"bufferViews/*/extensions/EXT_meshopt_compression/byteStride", {1, 256}},
    {"bufferViews/*/extensions/EXT_meshopt_compression/count", kCount},
    {"buffers/*/extensions/EXT_meshopt_compression/fallback", kBoolean},
    // KHR_draco_mesh_compression: the compressed view and the attributes' unique ids in it.
    {"meshes/*/primitives/*/extensions/KHR_draco_mesh_compression/bufferView", kIndex},
    {"meshes/*/primitives/*/extensions/KHR_draco_mesh_compression/attributes/*", kIndex},
    // Appearance.
    {"nodes/*/camera", kIndex, "the node has no camera"},
    {"nodes/*/extensions/KHR_lights_punctual/light", kIndex, "the node has no light", 1},
    {"meshes/*/primitives/*/material", kIndex, "the default material is used"},
    {"meshes/*/primitives/*/extensions/KHR_materials_variants/mappings/*/material", kIndex, "the mapping is ignored", 1},
    {"meshes/*/primitives/*/extensions/KHR_materials_variants/mappings/*/variants/*", kIndex, "the mapping is ignored", 2},
    {"materials/*/**/*Texture/index", kIndex, "it is drawn without that texture", 1},
    {"materials/*/**/*Texture/texCoord", kIndex, "it is drawn without that texture", 1},
    {"materials/*/**/*Texture/extensions/KHR_texture_transform/texCoord", kIndex, "the transform is ignored", 1},
    {"textures/*/source", kIndex, "textures using it are not drawn"},
    {"textures/*/sampler", kIndex, "the default sampler is used"},
    {"textures/*/extensions/*/source", kIndex, "the extension's image is ignored", 1},
    {"samplers/*/magFilter", {0, INT_MAX, 1, {9728, 9729}}, "the default is used"},
    {"samplers/*/minFilter", {0, INT_MAX, 1, {9728, 9729, 9984, 9985, 9986, 9987}}, "the default is used"},
    {"samplers/*/wrapS", {0, INT_MAX, 1, {33071, 33648, 10497}}, "REPEAT is used"},
    {"samplers/*/wrapT", {0, INT_MAX, 1, {33071, 33648, 10497}}, "REPEAT is used"},
};

std::vector<std::string_view> split(std::string_view path) {
  std::vector<std::string_view> out;
  for (size_t start = 0;;) {
    const size_t slash = path.find('/', start);
    out.push_back(path.substr(start, slash - start));
    if (slash == std::string_view::npos) return out;
    start = slash + 1;
  }
}

bool key_matches(std::string_view pattern, const std::string& key) {
  if (pattern == "*") return true;
  if (pattern.front() == '*') return key.size() >= pattern.size() - 1 && std::string_view(key).ends_with(pattern.substr(1));
  return pattern == key;
}

// The reference tokens from the document's root to the value being visited, pushed and popped by the walk:
// a JSON pointer is built only for a value that breaks a rule, not for each of a file's 200,000 nodes.
using Path = std::vector<std::string>;

json::json_pointer pointer_to(const Path& path) {
  json::json_pointer pointer;
  for (const std::string& token : path) pointer /= token;
  return pointer;
}

// Calls found(value, path) for every value of `node` that the rest of a rule's path matches. Depth is
// bounded by the nesting check that runs first (precheck.hpp).
template <typename Found>
void visit_matches(const json& node, std::span<const std::string_view> pattern, Path& at, Found& found) {
  if (pattern.empty()) {
    found(node, at);
    return;
  }
  const auto visit = [&](const json& child, std::span<const std::string_view> rest, std::string token) {
    at.push_back(std::move(token));
    visit_matches(child, rest, at, found);
    at.pop_back();
  };
  const std::string_view head = pattern.front();
  if (head == "**") {
    visit_matches(node, pattern.subspan(1), at, found);  // zero levels
    if (node.is_object()) {
      for (const auto& [key, value] : node.items())
        if (key != "extras") visit(value, pattern, key);
    } else if (node.is_array()) {
      for (size_t i = 0; i < node.size(); ++i) visit(node[i], pattern, std::to_string(i));
    }
    return;
  }
  if (node.is_object()) {
    if (head.front() != '*') {
      const auto it = node.find(std::string(head));
      if (it != node.end()) visit(*it, pattern.subspan(1), std::string(head));
      return;
    }
    for (const auto& [key, value] : node.items())
      if (key_matches(head, key)) visit(value, pattern.subspan(1), key);
  } else if (node.is_array() && head == "*") {
    for (size_t i = 0; i < node.size(); ++i) visit(node[i], pattern.subspan(1), std::to_string(i));
  }
}

bool meets(const json& value, const Constraint& c) {
  if (c.boolean) return value.is_boolean();
  if (!value.is_number_integer()) return false;  // fractions, 4.0, strings, booleans, null, objects
  // Above INT64_MAX only as unsigned, and out of every range then.
  if (value.is_number_unsigned() && value.get<uint64_t>() > uint64_t(INT64_MAX)) return false;
  const int64_t v = value.get<int64_t>();
  if (v < c.min || v > c.max || v % c.step != 0) return false;
  return c.allowed.size() == 0 || std::find(c.allowed.begin(), c.allowed.end(), v) != c.allowed.end();
}

// What a value must be to meet `c`, for the message about one that does not.
std::string requirement(const Constraint& c) {
  if (c.boolean) return "true or false";
  if (c.allowed.size()) {
    std::string want = "one of";
    for (int64_t a : c.allowed) want += (want.size() > 6 ? ", " : " ") + std::to_string(a);
    return want;
  }
  if (c.step > 1)
    return "a multiple of " + std::to_string(c.step) + " from " + std::to_string(c.min) + " to " + std::to_string(c.max);
  if (c.max == INT_MAX && c.min == 0) return "an index (an integer from 0 to " + std::to_string(INT_MAX) + ")";
  if (c.max == INT64_MAX) return "an integer of at least " + std::to_string(c.min);
  return "an integer from " + std::to_string(c.min) + " to " + std::to_string(c.max);
}

bool is_number(const std::string& token) {
  return !token.empty() && token.find_first_not_of("0123456789") == std::string::npos;
}

// The reference tokens of a JSON pointer, unescaped: "/a/b~1c" → a, b/c.
std::vector<std::string> tokens(json::json_pointer pointer) {
  std::vector<std::string> out;
  for (; !pointer.empty(); pointer.pop_back()) out.insert(out.begin(), pointer.back());
  return out;
}

// "accessors/3/byteOffset" → "accessor 3: byteOffset"; "meshes/0/primitives/1/attributes/POSITION" →
// "mesh 0 primitive 1: attributes.POSITION": the objects by kind and index as the loader's other messages
// name them, then the property.
std::string describe(const json::json_pointer& pointer) {
  static const std::pair<const char*, const char*> top[] = {
      {"accessors", "accessor"}, {"animations", "animation"}, {"buffers", "buffer"}, {"bufferViews", "bufferView"},
      {"cameras", "camera"},     {"images", "image"},         {"materials", "material"}, {"meshes", "mesh"},
      {"nodes", "node"},         {"samplers", "sampler"},     {"scenes", "scene"},       {"skins", "skin"},
      {"textures", "texture"}};
  static const std::pair<const char*, const char*> nested[] = {
      {"primitives", "primitive"}, {"channels", "channel"}, {"samplers", "sampler"}};
  const std::vector<std::string> parts = tokens(pointer);
  std::string owner, property;
  size_t i = 0;
  for (; i + 1 < parts.size() && is_number(parts[i + 1]); i += 2) {
    const auto* begin = i == 0 ? std::begin(top) : std::begin(nested);
    const auto* end = i == 0 ? std::end(top) : std::end(nested);
    const auto* kind = std::find_if(begin, end, [&](const auto& k) { return parts[i] == k.first; });
    if (kind == end) break;
    // Appended piece by piece: GCC 12 at -O3 reports a false -Wrestrict overlap for the chain of operator+.
    if (!owner.empty()) owner += ' ';
    owner.append(kind->second).append(" ").append(parts[i + 1]);
  }
  for (; i < parts.size(); ++i) property += is_number(parts[i]) ? "[" + parts[i] + "]" : (property.empty() ? "" : ".") + parts[i];
  return owner.empty() ? property : owner + ": " + property;
}

// A bad value as a message shows it: numbers, booleans and null as written, a string of at most 40 bytes,
// an object or array by its kind only (it may hold megabytes).
std::string quoted(const json& value) {
  if (value.is_object()) return "{...}";
  if (value.is_array()) return "[...]";
  if (value.is_string() && value.get_ref<const std::string&>().size() > 40)
    return json(value.get_ref<const std::string&>().substr(0, 40)).dump(-1, ' ', false, json::error_handler_t::replace) + "...";
  return value.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string sort_key(const json::json_pointer& pointer) {
  std::string key;
  for (const std::string& token : tokens(pointer))
    key += "/" + (is_number(token) ? std::string(20 - std::min<size_t>(token.size(), 20), '0') + token : token);
  return key;
}

}  // namespace

std::vector<std::string> check_schema_values(json& doc) {
  struct Drop {
    json::json_pointer at;
    std::string warning;
    std::string order;  // the pointer with array indices zero-padded, so that text order is index order
  };
  std::vector<Drop> drops;
  for (const Rule& rule : kRules) {
    const std::vector<std::string_view> pattern = split(rule.path);
    auto found = [&](const json& value, const Path& path) {
      if (meets(value, rule.constraint)) return;
      const json::json_pointer at = pointer_to(path);
      const std::string problem = describe(at) + " " + quoted(value) + " must be " + requirement(rule.constraint);
      if (!rule.consequence) throw InputError(problem);
      json::json_pointer owner = at;
      for (int k = 0; k < rule.drop_levels; ++k) owner = owner.parent_pointer();
      drops.push_back({owner, problem + "; " + rule.consequence, sort_key(owner)});
    };
    Path path;
    visit_matches(doc, pattern, path, found);
  }
  // Warnings ordered by where they are; values removed last to first, so that erasing an array element (a
  // variant mapping) leaves the pointers still to be removed valid. Two rules may drop the same object.
  std::stable_sort(drops.begin(), drops.end(), [](const Drop& a, const Drop& b) { return a.order < b.order; });
  std::vector<std::string> warnings;
  for (const Drop& d : drops) warnings.push_back(d.warning);
  // One removal per object: after an array element is erased, its pointer names the next one.
  drops.erase(std::unique(drops.begin(), drops.end(), [](const Drop& a, const Drop& b) { return a.order == b.order; }),
              drops.end());
  for (auto it = drops.rbegin(); it != drops.rend(); ++it) {
    if (!doc.contains(it->at)) continue;  // inside something already removed
    json& parent = doc.at(it->at.parent_pointer());
    if (parent.is_object()) parent.erase(it->at.back());
    else parent.erase(size_t(std::stoul(it->at.back())));
  }
  return warnings;
}

}  // namespace dqskin::gltf
