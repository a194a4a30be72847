// Texture outputs of `dqskin bake` (docs/DESIGN.md §4.1, §4.3): the BoneTexture the compute shader reads,
// as an RGBA32F OpenEXR image with a JSON side file (docs/DESIGN.md §4.1), and the order in which a
// vertex-animation texture holds the vertices (the VAT writers are lib/texture's). OpenImageIO stays out of
// this header.
#pragma once

#include "dqskin/atomic_file.hpp"
#include "dqskin/bone_texture.hpp"

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace dqskin {

// One mesh primitive whose vertices a VAT holds, in the order the texture holds them.
struct VatSource {
  int node = -1;
  int mesh = -1;
  int primitive = -1;  // index in the mesh's primitives
  size_t vertices = 0;
  std::string node_name, mesh_name;
  std::vector<int> shared_by;  // later primitives of the mesh drawing these same vertices (vertex_sharing.hpp)
};

// The primitives of `instances` that write vertices, in the order deform_frame and frame_view give them:
// instances in order, each instance's primitives in mesh order, less those that share an earlier
// primitive's vertex data (listed in its shared_by).
std::vector<VatSource> vat_sources(const Asset& asset, const std::vector<MeshInstance>& instances);

// Writes the BoneTexture of skin `skin` exactly as the shader reads it: an RGBA32F EXR of joints·T × frames
// texels holding texture.rgba bit for bit, and a JSON side file naming the skin, its joint names in order,
// T, the frame count, frame times (`times`, one per frame) and fps (0: not a grid, the JSON says null).
// Commits both files with `overwrite` (image first; with kRefuseDifferent both are compared before either
// is renamed) and returns what happened to each, image then JSON. Throws OutputError naming the file.
std::vector<Committed> write_bone_texture(const std::string& exr_path, const std::string& json_path,
                                          const BoneTexture& texture, const Asset& asset, int skin,
                                          std::span<const double> times, double fps, const CommitOptions& options);

}  // namespace dqskin
