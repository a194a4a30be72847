// The vertex-animation-texture (VAT) formats dqskin writes (internal to lib/texture and lib/bake): a
// runtime's layout chosen by profile, the texel type, where normals go, and the geometry of the image,
// texel by texel. docs/formats.md, "Vertex-animation textures", documents each with its reading shader.
//
//   dqskin   docs/DESIGN.md §4.3: absolute world-space positions, frame-major rows.
//   openvat  The OpenVAT Blender add-on and its engine kits (sharpen3d/openvat): offsets from the rest
//            mesh in Blender's Z-up axes, remapped per axis to [0, 1] by the side file's Min and Max;
//            one row per vertex wrap, frames down the rows of a wrap; normals n·0.5+0.5, packed into the
//            lower half of the same image or in a `_vnrm` image.
//   houdini  SideFX Labs Vertex Animation Textures 3.0, "Soft-Body Deformation" mode (Houdini's right-handed
//            Y-up axes, 1 unit = 1 metre): offsets from the clip's first frame, frame-major rows; normals as
//            the rotation texture `_rot` or packed into the position alpha.
#pragma once

#include "texel_encoding.hpp"

#include <glm/vec2.hpp>

#include <cstddef>
#include <string>

namespace dqskin::texture {

enum class VatProfile { kDqskin, kOpenVat, kHoudini };
bool parse_vat_profile(const std::string& text, VatProfile& profile);
const char* to_string(VatProfile profile);

// Where the normals go.
//   none      no normals
//   separate  their own image (dqskin: vat_normals, openvat: _vnrm, houdini: the rotation texture _rot)
//   packed    as the profile packs them: openvat the lower half of the position image, houdini a 10-bit
//             spheremap code in the position alpha
//   oct8      (dqskin) octahedral (u, v) in the RG channels of an 8-bit PNG beside the positions
//   oct16     (dqskin) the same in 16 bits
enum class NormalMode { kNone, kSeparate, kPacked, kOct8, kOct16 };
bool parse_normal_mode(const std::string& text, NormalMode& mode);
const char* to_string(NormalMode mode);

struct VatFormat {
  VatProfile profile = VatProfile::kDqskin;
  TexelType type = TexelType::kFloat32;
  NormalMode normals = NormalMode::kSeparate;
};

// The profile's own defaults: dqskin float with separate normals (today's output), openvat half with
// packed normals (the add-on's EXR16 and PACKED defaults), houdini float with the rotation texture.
VatFormat default_format(VatProfile profile);

// Why `format` cannot be written (an empty string when it can), as a sentence for a one-line error:
// octahedral normals belong to dqskin, houdini's packed normals need float or half, and so on.
std::string unsupported_reason(const VatFormat& format);

// Where one texel is: the page (image file), x to the right, y down from the first row of that file.
struct TexelAt {
  size_t x = 0, y = 0;
  size_t page = 0;
};

// The geometry of one clip's VAT images (positions, and normals when separate: both the same size).
struct VatLayout {
  VatFormat format;
  size_t vertices = 0;
  size_t frames = 0;
  size_t wrap = 0;            // W: vertices per row
  size_t wraps = 0;           // R: rows one frame's vertices take
  size_t width = 0, height = 0;            // a (full) page's image, padding included
  size_t used_width = 0, used_height = 0;  // the texels that hold data (top-left) in a full page
  // Frames split over several images when one would be higher than --max-size (dqskin only): pages of
  // frames_per_page frames each, the last with the rest.
  size_t frames_per_page = 0;
  size_t pages = 1;

  size_t page_of(size_t f) const { return f / frames_per_page; }
  size_t page_first_frame(size_t page) const { return page * frames_per_page; }
  size_t page_frames(size_t page) const;
  // The height of a page's image (padding included): a full page's, or the last page's own.
  size_t page_height(size_t page) const;

  // Vertex v of frame f in the position image (and the normal image when separate).
  TexelAt position(size_t v, size_t f) const;
  // Vertex v's normal at frame f when packed in the lower half (openvat); else as position().
  TexelAt packed_normal(size_t v, size_t f) const;
  // TEXCOORD_1 of vertex v in the rest mesh, as the profile's shader expects it in glTF's convention
  // (origin top-left, v down): dqskin the integer texel (v % W, v / W) of frame 0, for texelFetch;
  // openvat and houdini the texel centre of frame 0 in [0, 1]² (houdini's over the unpadded texels, as
  // its shader scales by the active-pixel ratios).
  glm::dvec2 lookup_uv(size_t v) const;
  // The rows frame f's texels lie in, in its page's image: [first, first + count). Frame-major layouts
  // (dqskin, houdini) give the frame's own rows, so frames stream in order; openvat's lie in every wrap:
  // the whole image.
  struct Rows {
    size_t first = 0, count = 0;
  };
  Rows frame_rows(size_t f) const;
  bool frame_major() const { return format.profile != VatProfile::kOpenVat; }
  // Channels of the position image: RGBA for dqskin float/half (w = 1) and houdini packed; RGB otherwise.
  int position_channels() const;
};

// The largest --max-size the command line takes (2^20 texels a side).
inline constexpr size_t kLargestMaxSize = size_t(1) << 20;

// Chooses the layout. `max_size` bounds both sides of the image (0: no bound, which for dqskin and houdini
// wraps rows at 8192 texels and leaves the height free, and for openvat keeps one row per vertex, its
// `use_single_row`). Within a bound every profile wraps a frame's vertices over several rows (openvat as
// its add-on's calculate_optimal_vat_resolution does) and dqskin splits frames over pages; houdini and
// openvat, whose runtimes read one image, do not page. `pot` pads both sides to powers of two. Throws
// InputError (naming `what`) when the vertices or frames cannot fit, with the size they need and the
// smallest --max-size that would fit it.
VatLayout plan_vat_layout(const VatFormat& format, size_t vertices, size_t frames, size_t max_size, bool pot,
                          const std::string& what);

// A page's file name: `name` itself for a single page, else "<stem>_page<k><extension>".
std::string page_file_name(const std::string& name, size_t page, size_t pages);

}  // namespace dqskin::texture
