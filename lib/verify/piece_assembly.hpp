// The files a sharded bake wrote in pieces (job/file_pieces.hpp), assembled by `dqskin merge` into the
// files one process writes (docs/DESIGN.md §6.5): each EXR image spliced from its shards' rows
// (texture/exr_rows.hpp), each side file's template filled with the decode-back figures of every slice,
// which add up (texture::DecodeShare). Runs after the folder was verified against the shards' manifests.
#pragma once

#include "manifest_set.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace dqskin::verify_detail {

// Writes the whole files of the pieces `shards` list into `folder` and makes `merged` (their merged
// manifest) list them instead of the pieces, with each animation's decode_check from the shards' shares.
// Returns the pieces' paths (relative to the folder), for the caller to delete once the merged manifest is
// in. Pieces that do not make a whole file are refusals naming the file.
std::vector<std::string> assemble_pieces(const std::string& folder, const std::vector<const JobManifest*>& shards,
                                         nlohmann::json& merged, std::vector<std::string>& refusals);

}  // namespace dqskin::verify_detail
