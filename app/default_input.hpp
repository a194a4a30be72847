// The rig `dqskin bake` bakes when given no input (README's first command), built into the binary from
// testdata/ so that an installed dqskin needs no source tree.
#pragma once

#include <string_view>

namespace dqskin::cli {

extern const std::string_view kDefaultInput;      // the .gltf file's bytes (buffers as data URIs)
extern const char* const kDefaultInputName;       // its file name

}  // namespace dqskin::cli
