// The rig `dqskin bake` and `dqskin render` work on when given no input (the README's first command),
// built into the binary from testdata/ so that an installed dqskin needs no source tree.
#pragma once

#include <string>
#include <string_view>

namespace dqskin::cli {

extern const std::string_view kDefaultInput;      // the .gltf file's bytes (buffers as data URIs)
extern const char* const kDefaultInputName;       // its file name

// Writes the bundled rig into a new temporary folder (TMPDIR/dqskin-COMMAND-XXXXXX) and returns its path.
// An empty `out_dir` becomes that folder's "out". Says so on stderr unless `quiet`. Throws OutputError
// naming the folder or file it cannot write.
std::string unpack_default_input(const std::string& command, std::string& out_dir, bool quiet);

}  // namespace dqskin::cli
