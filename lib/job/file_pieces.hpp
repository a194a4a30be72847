// The pieces a shard writes of files that `dqskin merge` assembles (docs/DESIGN.md §6.5), named as the
// texture writers name them: rows of an EXR image ("vat_positions.exr.rows-144-288", texture::
// piece_file_name) and a side file awaiting the figures of every slice ("vat.json.template",
// texture::template_file_name). The bake lists them in its shard manifest; the merge reads that list.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace dqskin {

struct FilePiece {
  enum class Kind { kExrRows, kDecodeCheck };
  std::string whole;  // the file it is a piece of, relative to the output folder
  Kind kind = Kind::kExrRows;
  size_t first_row = 0, end_row = 0;  // kExrRows: the image's rows it holds
  std::string texture;                // kDecodeCheck: whose figures go in, "vat" or "bones_skin<K>"
};

// The piece `path` (relative to the output folder) is, or none.
std::optional<FilePiece> file_piece(const std::string& path);

// How the manifest names a kind: "exr_rows", "decode_check".
const char* to_string(FilePiece::Kind kind);

}  // namespace dqskin
