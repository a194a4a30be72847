#include "piece_assembly.hpp"

#include "../job/file_pieces.hpp"
#include "../base/sha256.hpp"
#include "../texture/exr_rows.hpp"
#include "../texture/vat_check.hpp"
#include "../texture/vat_side_files.hpp"
#include "dqskin/atomic_file.hpp"
#include "dqskin/error.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

namespace dqskin::verify_detail {
namespace {

using nlohmann::json;

struct Listed {
  const json* record;
  std::string shard;  // the manifest that lists it, for messages
};

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw InputError(path + ": cannot be read");
  return text.str();
}

// The figures of texture `texture` of animation (input, clip): the shares of every shard added up, which
// must cover the animation's `frames` frames once (each share names its slice's frames, "slice": [first, end]). Throws InputError
// naming the shard whose share is malformed, or saying which frames no share covers.
texture::DecodeShare added_shares(const std::vector<const JobManifest*>& shards, size_t input, size_t clip,
                                  const std::string& texture, size_t frames) {
  std::vector<std::pair<std::pair<size_t, size_t>, texture::DecodeShare>> slices;
  for (const JobManifest* shard : shards) {
    const json& inputs = shard->json["inputs"];
    if (input >= inputs.size() || !inputs[input].contains("animations")) continue;
    const json& clips = inputs[input]["animations"];
    if (clip >= clips.size() || !clips[clip].contains("decode_check_share")) continue;
    const std::string what = shard->name + ": inputs[" + std::to_string(input) + "].animations[" + std::to_string(clip) +
                             "].decode_check_share";
    const json& shares = clips[clip]["decode_check_share"];
    if (!shares.is_object()) throw InputError(what + " is not an object");
    if (!shares.contains(texture)) continue;
    const json range = shares[texture].is_object() ? shares[texture].value("slice", json()) : json();
    if (!range.is_array() || range.size() != 2 || !range[0].is_number_unsigned() || !range[1].is_number_unsigned())
      throw InputError(what + "." + texture + ".slice is not [first, end]");
    slices.emplace_back(std::pair(range[0].get<size_t>(), range[1].get<size_t>()),
                        texture::DecodeShare::from_json(shares[texture], what + "." + texture));
  }
  std::sort(slices.begin(), slices.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  texture::DecodeShare sum;
  size_t covered = 0;
  for (const auto& [range, share] : slices) {
    if (range.first != covered || range.second <= range.first) break;
    covered = range.second;
    sum.merge(share);
  }
  if (covered != frames)
    throw InputError("the shards' figures of texture " + texture + " of inputs[" + std::to_string(input) + "].animations[" +
                     std::to_string(clip) + "] do not cover its " + std::to_string(frames) +
                     " frames once (from frame " + std::to_string(covered) + ")");
  return sum;
}

// Frames of animation (input, clip) in the merged manifest.
size_t animation_frames(const json& merged, size_t input, size_t clip) {
  const json& inputs = merged["inputs"];
  if (input >= inputs.size() || !inputs[input].contains("animations") || clip >= inputs[input]["animations"].size())
    return 0;
  const json times = inputs[input]["animations"][clip].value("frame_times", json());
  return times.is_array() ? times.size() : 0;
}

// As manifest.json records a texture's figures: the side files' members (DecodeCheck::to_json), by name.
json manifest_figures(const texture::DecodeCheck& d) { return json(d.to_json()); }

}  // namespace

std::vector<std::string> assemble_pieces(const std::string& folder, const std::vector<const JobManifest*>& shards,
                                         json& merged, std::vector<std::string>& refusals) {
  std::map<std::string, std::vector<Listed>> wholes;  // whole file → its pieces
  std::vector<std::string> pieces;
  for (const JobManifest* shard : shards) {
    if (!shard->json.contains("pieces")) continue;
    // A piece must be one of the shard's outputs (verified: inside the folder, as listed), named as the bake
    // names pieces, of the whole file it says: the merge writes and deletes nothing else.
    std::set<std::string> outputs;
    for (const json& out : shard->json["outputs"])
      if (out.is_object() && out.value("path", json()).is_string()) outputs.insert(out["path"].get<std::string>());
    const json& listed = shard->json["pieces"];
    for (size_t i = 0; i < (listed.is_array() ? listed.size() : 1); ++i) {
      const json& p = listed.is_array() ? listed[i] : listed;
      const std::string path = p.is_object() && p.value("path", json()).is_string() ? p["path"].get<std::string>() : "";
      const std::optional<FilePiece> piece = file_piece(path);
      if (!piece || !outputs.count(path) || p.value("whole", json()) != piece->whole ||
          p.value("splice", json()) != to_string(piece->kind)) {
        refusals.push_back(folder + "/" + shard->name + ": pieces[" + std::to_string(i) +
                           "] is not a piece of a file among the shard's outputs");
        continue;
      }
      wholes[piece->whole].push_back({&p, shard->name});
      pieces.push_back(path);
    }
  }
  if (!refusals.empty()) return pieces;

  // Each animation's figures, from the shares of every slice.
  for (size_t i = 0; i < merged["inputs"].size(); ++i) {
    json& in = merged["inputs"][i];
    if (!in.contains("animations")) continue;
    for (size_t c = 0; c < in["animations"].size(); ++c) {
      json& clip = in["animations"][c];
      std::set<std::string> textures;
      for (const JobManifest* shard : shards) {
        const json& inputs = shard->json["inputs"];
        if (i < inputs.size() && inputs[i].contains("animations") && c < inputs[i]["animations"].size() &&
            inputs[i]["animations"][c].contains("decode_check_share") &&
            inputs[i]["animations"][c]["decode_check_share"].is_object())
          for (const auto& [texture, share] : inputs[i]["animations"][c]["decode_check_share"].items()) textures.insert(texture);
      }
      clip.erase("decode_check_share");
      try {
        for (const std::string& texture : textures)
          clip["decode_check"][texture] =
              manifest_figures(added_shares(shards, i, c, texture, animation_frames(merged, i, c)).figures());
      } catch (const InputError& e) {
        refusals.push_back(folder + "/" + e.what());
      }
    }
  }

  std::map<std::string, json> written;  // whole file → its output record
  for (auto& [whole, listed] : wholes) {
    const std::string path = folder + "/" + whole;
    try {
      AtomicFile file(path);
      const std::string kind = listed.front().record->value("splice", "");
      if (kind == "exr_rows") {
        std::vector<std::pair<size_t, std::string>> rows;  // first row (from the piece's name), path
        for (const Listed& l : listed) {
          const std::string piece = l.record->value("path", "");
          rows.emplace_back(file_piece(piece)->first_row, folder + "/" + piece);
        }
        std::sort(rows.begin(), rows.end());
        std::vector<std::string> paths;
        for (auto& [first, p] : rows) paths.push_back(p);
        texture::splice_exr_rows(paths, [&](std::span<const char> bytes) { file.write(bytes); });
      } else if (kind == "decode_check") {
        if (listed.size() != 1) throw InputError("more than one shard wrote its template");
        const json& r = *listed.front().record;
        const json input = r.value("input", json()), clip = r.value("animation", json()), texture = r.value("texture", json());
        if (!input.is_number_unsigned() || !clip.is_number_unsigned() || !texture.is_string())
          throw InputError("its template names no animation and texture");
        const texture::DecodeShare sum = added_shares(shards, input.get<size_t>(), clip.get<size_t>(), texture.get<std::string>(),
                                                      animation_frames(merged, input.get<size_t>(), clip.get<size_t>()));
        const std::string piece = folder + "/" + r.value("path", "");
        file.write(texture::with_decode_check(read_text(piece), sum.figures(), piece));
      } else {
        throw InputError("its pieces are of a kind this version does not splice");
      }
      file.commit();
      written[whole] = {{"path", whole}, {"size", uint64_t(std::filesystem::file_size(path))}, {"sha256", sha256_file(path)}};
    } catch (const std::exception& e) {
      refusals.push_back(path + ": cannot be assembled from its pieces: " + e.what());
    }
  }
  // A refusal leaves the folder as it was: the files assembled so far go.
  if (!refusals.empty()) {
    for (const auto& [whole, record] : written) {
      std::error_code ignored;
      std::filesystem::remove(folder + "/" + whole, ignored);
    }
    return pieces;
  }

  // The outputs: the pieces out, the whole files in, by path as the bake lists them.
  const std::set<std::string> piece_set(pieces.begin(), pieces.end());
  json outputs = json::array();
  for (const json& out : merged["outputs"])
    if (!piece_set.count(out.value("path", ""))) outputs.push_back(out);
  for (auto& [whole, record] : written) outputs.push_back(std::move(record));
  std::stable_sort(outputs.begin(), outputs.end(),
                   [](const json& a, const json& b) { return a.value("path", "") < b.value("path", ""); });
  merged["outputs"] = std::move(outputs);
  return pieces;
}

}  // namespace dqskin::verify_detail
