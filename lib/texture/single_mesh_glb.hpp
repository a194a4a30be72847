// What the meshes that ship beside textures (rest_glb.hpp, bones_mesh_glb.hpp) have in common: one node
// with no transform drawing one mesh, the source's primitives with their topology as the frames have it.
#pragma once

#include "../io/glb_appearance.hpp"

#include "dqskin/asset.hpp"

#include <string>

namespace dqskin::texture {

// Puts `source`'s indices (and mode) on `primitive`: triangle strips and fans as triangle lists, other
// modes as the source has them.
void add_topology(const Primitive& source, glb::BinWriter& bin, glb::json& primitive);

// The .glb bytes of one scene with one node `name`, no transform, drawing one mesh `name` of `primitives`
// over `bin`. No material: a viewer draws its default. The buffer's byteLength is the data's; the
// container pads the chunk itself (§4.4.3.3).
std::string single_mesh_glb(glb::json primitives, glb::BinWriter bin, const std::string& name);

}  // namespace dqskin::texture
