// What the meshes that ship beside textures (rest_glb.hpp, bones_mesh_glb.hpp) have in common: one node
// with no transform drawing one mesh, the source's primitives with their topology as the frames have it.
#pragma once

#include "../write/glb_appearance.hpp"

#include "dqskin/asset.hpp"

#include <string>

namespace dqskin::texture {

// Puts `source`'s material on `primitive` when `look` has it (its index is the source's).
void add_material(const Primitive& source, const glb::Appearance* look, glb::json& primitive);

// COLOR_0 as float RGBA clamped to [0, 1], as §3.7.2.1 requires of float colours; returns the accessor.
int colors_accessor(const std::vector<glm::vec4>& colors, glb::BinWriter& bin);

// Puts `source`'s indices (and mode) on `primitive`: triangle strips and fans as triangle lists, other
// modes as the source has them.
void add_topology(const Primitive& source, glb::BinWriter& bin, glb::json& primitive);

// Whether `look` (glb::read_look, or null) has materials to draw with. Without, the writers below write
// what they wrote before there was a look: no material, and a viewer draws its default.
bool has_materials(const glb::Appearance* look);

// The .glb bytes of one scene with one node `name`, no transform, drawing one mesh `name` of `primitives`
// over `bin`. With a look that has materials (has_materials), `bin` must start with the look's own (its
// images) and the document takes its materials, textures, samplers and images, which the primitives'
// `material` indices and TEXCOORD_n serve; else the buffer's byteLength is the data's and the container
// pads the chunk itself (§4.4.3.3).
std::string single_mesh_glb(glb::json primitives, glb::BinWriter bin, const std::string& name,
                            const glb::Appearance* look = nullptr);

}  // namespace dqskin::texture
