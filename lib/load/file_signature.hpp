// What a file that is not glTF looks like, for the one line that refuses it: users meet HTML error pages
// and ZIP archives saved as .glb, and a JSON parser's "invalid literal" says nothing about that.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace dqskin::gltf {

// For bytes that are neither a GLB (magic "glTF", §4.4.2) nor JSON text whose first value is an object (a
// glTF document is one, §5.1): "is not a glTF file: it is a ZIP archive" for the signatures users meet,
// else "is not a glTF file: it starts with '<!DOCTYPE html>'" (its first line, at most 24 bytes, printable).
// None for a GLB, for text opening with '{' (after whitespace and a UTF-8 byte order mark), and for a file
// of whitespace only, which the JSON parser reports as empty.
std::optional<std::string> not_gltf_reason(std::span<const uint8_t> bytes);

}  // namespace dqskin::gltf
