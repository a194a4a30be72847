// Reading a glTF file into a tinygltf::Model with file access that cannot hang or exhaust memory
// (internal to the loader).
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <span>
#include <string>

namespace dqskin::gltf {

// Parses .glb or .gltf bytes (chosen by the GLB magic). External buffers are read from base_dir, only
// when they are regular files of at most max_file_bytes. Images are kept encoded, not decoded.
// Throws InputError.
tinygltf::Model parse_model(std::span<const uint8_t> bytes, const std::string& base_dir, uint64_t max_file_bytes);

// Reads a whole regular file of at most max_bytes. Throws InputError, whose message does not repeat the
// path.
std::vector<uint8_t> read_regular_file(const std::string& path, uint64_t max_bytes);

}  // namespace dqskin::gltf
