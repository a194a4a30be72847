// The metadata written beside a vertex-animation texture (internal to lib/texture and lib/bake): dqskin's
// own JSON, complete for every profile, and the side file each profile's runtime reads (OpenVAT's
// `-remap_info.json`, Houdini's `_data.json`), plus the file names each profile uses.
#pragma once

#include "vat_codec.hpp"

#include "texture_output.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace dqskin::texture {

// The files of one clip's VAT, relative to the clip's folder; empty names are not written.
struct VatFileNames {
  std::string positions, normals, rest_mesh, profile_side_file;
  std::string dqskin_side_file = "vat.json";
};
// dqskin: vat_positions.<ext>, vat_normals.<ext>, rest.glb; openvat: <asset>_vat.<ext>, <asset>_vnrm.<ext>,
// <asset>.glb, <asset>-remap_info.json; houdini: <asset>_pos.<ext>, <asset>_rot.<ext>, <asset>_mesh.glb,
// <asset>_data.json. `asset` is a file-name-safe name of the input.
VatFileNames vat_file_names(const VatFormat& format, const std::string& asset);

// The decode-back check's figures for one texture (also recorded in manifest.json).
struct DecodeCheck {
  double max_error = 0, p99_error = 0;              // at the baked frames, scene units
  double max_midpoint_error = 0, p99_midpoint_error = 0;  // between frames, linearly interpolated
  double max_normal_degrees = 0;                    // at the baked frames
  double max_midpoint_normal_degrees = 0;           // between frames (the normals interpolated, renormalized)
  size_t samples = 0;                               // vertex samples compared
  nlohmann::ordered_json to_json() const;
};

// One clip of a texture: frames first_frame … first_frame + frame_count − 1 (docs/DESIGN.md §4.9).
struct VatClipEntry {
  std::string name;
  size_t first_frame = 0, frame_count = 0;
  double fps = 0;       // 0: the clip's times are not a grid
  double duration = 0;  // from its first frame to its last, seconds
  bool loops = false;   // its last frame's pose equals its first's
};

// What the metadata says about the animation.
struct VatClipInfo {
  std::string asset;  // the input's name
  std::string clip;   // the clip's name; empty for several
  std::vector<double> times;  // every frame's time in its clip, the clips one after another
  double fps = 0;  // 0: the times are not a grid, or the clips' rates differ
  bool loops = false;  // one clip: its last frame's pose equals its first's
  std::vector<VatClipEntry> clips;  // the clip table: one entry, or one per clip with --combine-clips
  std::vector<DecodeCheck> clip_checks;  // several clips: each clip's decode-back figures, in table order
  std::vector<VatSource> sources;
  std::vector<Box> frame_bounds;  // the animated mesh at each frame, glTF world space
  Box clip_bounds;                // over the clip
  // What the planner chose, when it ran (--max-error, --max-bytes).
  struct Plan {
    std::string type;
    size_t step = 1;  // every step-th frame of the clip's grid
    double expected_error = 0, encoding_error = 0, interpolation_error = 0;
    uint64_t bytes = 0;  // GPU memory of the images
  };
  std::optional<Plan> plan;
};

// Bounds for remapping that the shader reads back exactly: `box` widened outward to a decimal grid of
// about four significant digits of its widest side (OpenVAT rounds to 0.1 the same way), so that the
// side file prints short numbers whose float values are those the encoder used.
Box decimal_bounds(const Box& box);

// Houdini VAT 3.0's bounds with its shader data embedded (TEXTURE/embed_data_to_bounds): the clip's
// bounds snapped outward to 0.1, then the HDR flag and rows per frame in the fractional parts of max.z
// and min.y, and the active-pixel ratios of a padded image in min.z and min.x. Throws InputError naming
// `what` for more than 899 rows per frame, which that code cannot hold.
Box houdini_encoded_bounds(const Box& clip_bounds, const VatLayout& layout, const std::string& what);

// A side file written without its figures (a slice's template, VatSlice) with them: what vat_json and the
// bone textures' writer write with a check, byte for byte (the figures are the document's last member).
// Throws InputError naming `what` when `json_text` is not a JSON object.
std::string with_decode_check(const std::string& json_text, const DecodeCheck& check, const std::string& what);

// dqskin's JSON: everything a runtime or a person needs, for every profile.
std::string vat_json(const VatEncoding& e, const VatClipInfo& info, const VatFileNames& names,
                     const DecodeCheck* check);
// The profile's own side file (empty for dqskin).
std::string profile_side_file(const VatEncoding& e, const VatClipInfo& info);

}  // namespace dqskin::texture
