// Reading a glTF file into a tinygltf::Model with file access that cannot hang, exhaust memory or leave
// the model's resource root (internal to the loader).
#pragma once

#include "dqskin/load.hpp"

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace dqskin::gltf {

struct ParsedModel {
  tinygltf::Model model;
  nlohmann::json doc;  // the file's JSON as checked (precheck_json): what the model was read from
  std::vector<std::string> warnings;  // appearance values removed by the checks, images not read
  uint64_t json_bytes = 0;            // what parsing the JSON took (json_memory), for the memory estimate
};

// Parses .glb or .gltf bytes (chosen by the GLB magic) after precheck.hpp's checks. External buffers and
// images are read relative to base_dir, only from inside the resource root (base_dir and
// options.resource_roots), only when they are regular files of at most options.max_file_bytes. Images are
// kept encoded, not decoded. Throws InputError.
ParsedModel parse_model(std::span<const uint8_t> bytes, const std::string& base_dir, const LoadOptions& options);

// What the .glb writer copies from the file (source_document.hpp), out of `parsed` (its JSON is moved)
// and the asset made of it. Attributes are read under `options`' limits.
std::shared_ptr<const SourceDocument> keep_source(ParsedModel& parsed, const Asset& asset, const LoadOptions& options);

// The folder a model's relative URIs start from: "dir" for "dir/model.gltf", "/" for "/model.gltf", "."
// for "model.gltf".
std::string folder_of(const std::string& path);

// Reads a whole regular file of at most max_bytes. Checks what it opened (a FIFO or device is refused
// without waiting for a writer or reading forever). Throws InputError, whose message does not repeat the
// path.
std::vector<uint8_t> read_regular_file(const std::string& path, uint64_t max_bytes);

}  // namespace dqskin::gltf
