// Parsing KHR_animation_pointer's JSON pointers (RFC 6901) into the properties dqskin animates, and
// restoring the channels tinygltf does not keep (animation_pointer.hpp).
#include "animation_pointer.hpp"

#include <nlohmann/json.hpp>

#include <vector>

namespace dqskin::gltf {
namespace {

constexpr const char* kExtension = "KHR_animation_pointer";

// The reference tokens of `pointer`, unescaped (RFC 6901 §3-4: "~1" is '/', "~0" is '~', any other '~'
// is an error). False when `pointer` is not a JSON pointer (non-empty and not starting with '/').
bool split_tokens(std::string_view pointer, std::vector<std::string>& tokens, std::string& problem) {
  if (pointer.empty() || pointer.front() != '/') {
    problem = "does not start with '/'";
    return false;
  }
  tokens.emplace_back();
  for (size_t i = 1; i < pointer.size(); ++i) {
    const char c = pointer[i];
    if (c == '/') {
      tokens.emplace_back();
    } else if (c == '~') {
      const char next = i + 1 < pointer.size() ? pointer[i + 1] : '\0';
      if (next != '0' && next != '1') {
        problem = "has '~' not followed by 0 or 1";
        return false;
      }
      tokens.back() += next == '0' ? '~' : '/';
      ++i;
    } else {
      tokens.back() += c;
    }
  }
  return true;
}

// An array index as RFC 6901 §4 writes it: "0", or digits without a leading zero; at most 9 digits
// (tinygltf and the loader index with int).
bool array_index(const std::string& token, size_t& index) {
  if (token.empty() || token.size() > 9 || (token.size() > 1 && token.front() == '0')) return false;
  index = 0;
  for (char c : token) {
    if (c < '0' || c > '9') return false;
    index = index * 10 + size_t(c - '0');
  }
  return true;
}

}  // namespace

AnimationPointer parse_animation_pointer(std::string_view pointer) {
  AnimationPointer out;
  std::vector<std::string> tokens;
  if (!split_tokens(pointer, tokens, out.problem)) return out;
  if (tokens.size() < 2 || (tokens[0] != "nodes" && tokens[0] != "meshes")) return out;  // another object
  const bool node = tokens[0] == "nodes";
  if (!array_index(tokens[1], out.index)) {
    out.problem = std::string("names ") + (node ? "node" : "mesh") + " '" + tokens[1] + "', which is not an array index";
    return out;
  }
  if (tokens.size() != 3) return out;  // the node or mesh itself, an element of an array, an extension's property
  const std::string& name = tokens[2];
  if (node && name == "translation") out.property = PointerProperty::kNodeTranslation;
  else if (node && name == "rotation") out.property = PointerProperty::kNodeRotation;
  else if (node && name == "scale") out.property = PointerProperty::kNodeScale;
  else if (node && name == "weights") out.property = PointerProperty::kNodeWeights;
  else if (!node && name == "weights") out.property = PointerProperty::kMeshWeights;
  return out;
}

const std::string* channel_pointer(const tinygltf::AnimationChannel& channel) {
  const auto it = channel.target_extensions.find(kExtension);
  if (it == channel.target_extensions.end() || !it->second.IsObject() || !it->second.Has("pointer")) return nullptr;
  const tinygltf::Value& pointer = it->second.Get("pointer");
  return pointer.IsString() ? &pointer.Get<std::string>() : nullptr;
}

void restore_channels(tinygltf::Model& model, const nlohmann::json& doc) {
  const auto animations = doc.find("animations");
  if (animations == doc.end() || !animations->is_array()) return;
  for (size_t a = 0; a < animations->size() && a < model.animations.size(); ++a) {
    const nlohmann::json& animation = (*animations)[a];
    const auto channels = animation.find("channels");
    std::vector<tinygltf::AnimationChannel> restored;
    if (channels != animation.end() && channels->is_array())
      for (const nlohmann::json& c : *channels) {
        tinygltf::AnimationChannel ch;
        if (!c.is_object()) {
          restored.push_back(std::move(ch));
          continue;
        }
        // precheck_json has checked that sampler and target.node, where present, are indices.
        if (const auto s = c.find("sampler"); s != c.end() && s->is_number_integer()) ch.sampler = s->get<int>();
        const auto target = c.find("target");
        if (target != c.end() && target->is_object()) {
          if (const auto n = target->find("node"); n != target->end() && n->is_number_integer())
            ch.target_node = n->get<int>();
          if (const auto p = target->find("path"); p != target->end() && p->is_string())
            ch.target_path = p->get<std::string>();
          const nlohmann::json* pointer = nullptr;
          if (const auto e = target->find("extensions"); e != target->end() && e->is_object())
            if (const auto k = e->find(kExtension); k != e->end() && k->is_object())
              if (const auto p = k->find("pointer"); p != k->end() && p->is_string()) pointer = &*p;
          if (pointer) {
            tinygltf::Value::Object extension{{"pointer", tinygltf::Value(pointer->get<std::string>())}};
            ch.target_extensions[kExtension] = tinygltf::Value(std::move(extension));
          }
        }
        restored.push_back(std::move(ch));
      }
    model.animations[a].channels = std::move(restored);
  }
}

}  // namespace dqskin::gltf
