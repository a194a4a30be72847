// The mesh that ships beside bone textures (internal to lib/texture and lib/bake): what a runtime that
// skins in its own vertex shader needs besides the texture. One glTF 2.0 binary with every skinned
// primitive as the source stores it (bind space: the joint matrices of the texture map it to world space),
// its influences, and which texture each primitive reads.
#pragma once

#include "../write/glb_appearance.hpp"

#include "dqskin/asset.hpp"
#include "dqskin/skinning.hpp"

#include <string>
#include <vector>

namespace dqskin::texture {

// The .glb bytes: one node `name` with no transform drawing one mesh whose primitives are those of the
// `instances` whose skin is not -1, in instance order. Each primitive has the source's POSITION, NORMAL (the
// smooth normals dqskin deforms where the source has none) and TEXCOORD_0 (morph targets are not applied: the textures hold joints only), the influences as the
// application-specific attributes `_JOINTS_0`/`_WEIGHTS_0` (and `_JOINTS_1`/`_WEIGHTS_1` for 8), indices
// into the skin's `joints` as the texture orders them, and `extras` {"skin": K, "bones": "bones_skinK"}:
// the texture's name without extension. Weights are as stored; the decode formulas normalize them. Plain
// JOINTS_n and a glTF skin would make every viewer skin the mesh itself, with its own blending (glTF 2.0
// §3.7.3.3), which is what the texture replaces. With a `look` that has materials (glb::read_look of the
// source), each primitive keeps its source material, TEXCOORD_1 and COLOR_0, the file the source's textures,
// samplers and images; without, no material. Deterministic.
std::string encode_bones_mesh_glb(const Asset& asset, const std::vector<MeshInstance>& instances,
                                  const std::string& name, const glb::Appearance* look = nullptr);

}  // namespace dqskin::texture
