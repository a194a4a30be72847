// The rest mesh that ships beside a vertex-animation texture (internal to lib/texture and lib/bake): one
// glTF 2.0 binary holding every baked primitive in world space, as the texture's offsets are measured
// from it, with TEXCOORD_1 telling each vertex where its texels are (VatLayout::lookup_uv). An importer
// that reorders, splits or welds vertices keeps each vertex's TEXCOORD_1, so the texture still finds it.
#pragma once

#include "vat_format.hpp"
#include "../write/glb_appearance.hpp"

#include "dqskin/frame_view.hpp"
#include "dqskin/skinning.hpp"

#include <string>
#include <vector>

namespace dqskin::texture {

// The .glb bytes: one node `name` with no transform drawing one mesh whose primitives are those of
// `instances` (in the VAT's vertex order; a primitive that shares an earlier one's vertex data names that
// one's accessors, as in the source: vertex_sharing.hpp), positions and normals from `rest` (every
// primitive, as frame_view gives them), the source's TEXCOORD_0 (or,
// where a primitive has none, a copy of TEXCOORD_1, since glTF numbers texture coordinate sets from 0)
// and TEXCOORD_1 from `layout`. With a `look` that has materials (glb::read_look of the source), each
// primitive keeps its source material and COLOR_0, the file the source's textures, samplers and images,
// and the source's TEXCOORD_1 becomes TEXCOORD_2, which the materials' texCoord 1 then names; without, no material
// (a viewer draws its default). Deterministic.
std::string encode_rest_glb(const Asset& asset, const std::vector<MeshInstance>& instances, const FrameView& rest,
                            const VatLayout& layout, const std::string& name, const glb::Appearance* look = nullptr);

}  // namespace dqskin::texture
