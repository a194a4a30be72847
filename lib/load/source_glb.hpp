// A glTF file opened for writing back as one .glb (internal to lib/load: lint --fix's fixed_glb.hpp and
// optimize's animation_glb.hpp). Its JSON document as read, every buffer concatenated into the BIN chunk
// being filled (glTF 2.0 §4.4: a .glb has one buffer, the BIN chunk, buffer 0 without uri) with every
// bufferView moved by its buffer's offset there, and external images embedded in views of their own.
#pragma once

#include "../asset/glb_container.hpp"
#include "dqskin/load.hpp"

#include <string>
#include <vector>

namespace dqskin::gltf {

struct SourceGlb {
  nlohmann::json doc;  // without "buffers"; bufferViews and accessors are in `bin`
  glb::BinWriter bin;
  std::vector<std::string> required;  // the source's extensionsRequired, less `own`
  std::vector<std::string> own;       // extensions the data needs without naming them (KHR_mesh_quantization)
};

// Throws InputError for a file that cannot be written back faithfully: compressed geometry, whose decoded
// data the writers do not re-encode, and unreadable buffers or images. `who` names the writer in messages
// ("--fix").
SourceGlb open_source_glb(const std::string& path, const LoadOptions& options, const std::string& who);

}  // namespace dqskin::gltf
