// Vertex positions and normals to texels and back, for each VAT profile (internal to lib/texture and
// lib/bake). The encoder fills the images a profile's files hold; the decoder reads texels exactly as the
// profile's shader does (docs/formats.md, "Vertex-animation textures"), in float as a GPU computes, so
// the decode-back check measures what a runtime will show.
#pragma once

#include "texel_image.hpp"
#include "vat_format.hpp"

#include "dqskin/frame_view.hpp"

#include <glm/vec3.hpp>

#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace dqskin::texture {

// A profile's axes from glTF's (right-handed, y up, metres): openvat stores Blender's z-up axes
// (x, −z, y); dqskin and houdini keep glTF's.
glm::dvec3 to_profile_axes(VatProfile profile, const glm::dvec3& gltf);
glm::dvec3 from_profile_axes(VatProfile profile, const glm::dvec3& stored);

// An axis-aligned box, empty until a point is added.
struct Box {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};
  void add(const glm::dvec3& p);
  void add(const Box& b);
  bool empty() const { return !(lo.x <= hi.x); }
  double diagonal() const;
};

// Everything decided before the first texel is written.
struct VatEncoding {
  VatLayout layout;
  // The mesh the offsets are taken from, 3 floats per vertex in glTF world space: the rest pose (openvat)
  // or the clip's first frame (houdini); empty for dqskin, which stores absolute positions.
  std::vector<float> rest;
  // Whether positions are remapped to [0, 1] by `bounds` (in the profile's axes): always for openvat, for
  // the PNG types of the others.
  bool remapped = false;
  Box bounds;
  // What is stored before any remapping, over the clip (profile axes): the magnitudes half rounds at.
  Box stored;
  // The EXR files' compression (texel_image.hpp exr_compression; empty: the type's default).
  std::string compression;

  bool stores_offsets() const { return !rest.empty(); }
  // The rows of the normal image, when the normals have their own: its texel type (oct8 and oct16 are
  // 8- and 16-bit PNGs whatever the positions are).
  std::optional<TexelType> normal_image_type() const;
};

// The position value the profile stores for vertex v before remapping (offset or absolute, profile axes).
glm::dvec3 stored_position(const VatEncoding& e, size_t v, const glm::vec3& position);

// The images' channel counts: positions (VatLayout::position_channels) and the normal image (4 for dqskin's
// float and half, xyz and w = 0, and for houdini's quaternions; 3 otherwise).
int normal_channels(const VatEncoding& e);

// Writes frame f's texels into `positions` and `normals` (the normal image, when the normals have one),
// bands that must hold the frame's rows (VatLayout::frame_rows). Several threads may encode distinct
// frames into one band. Throws InputError naming `what`, the frame and the vertex when a position or
// normal is not finite, or a value overflows half or falls outside the remap bounds (never clipped
// silently).
void encode_vat_frame(const VatEncoding& e, const FrameView& frame, size_t f, TexelImage& positions,
                      TexelImage* normals, const std::string& what);

// Frame f as the profile's shader decodes it from bands of the images read back (holding the frame's
// rows): world-space positions (glTF axes, 3 per vertex) and unit normals (3 per vertex; empty without
// normals).
void decode_vat_frame(const VatEncoding& e, const TexelImage& positions, const TexelImage* normals, size_t f,
                      std::vector<float>& out_positions, std::vector<float>& out_normals);

// The largest distance encoding can move a decoded position (scene units): per axis 0 for float, half's
// rounding at the axis's largest stored magnitude (or of the remapped [0, 1]), half a step of the remapped
// range for the integer types; their Euclidean sum over the three axes, plus the float arithmetic of the
// decode.
double position_encoding_bound(const VatEncoding& e);

}  // namespace dqskin::texture
