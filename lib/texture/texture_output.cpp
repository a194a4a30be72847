// The BoneTexture as an OpenEXR file with a JSON side file (docs/DESIGN.md §4.1: the dq
// profile of lib/texture's bone writer), and the vertex order of vertex-animation textures.
#include "texture_output.hpp"
#include "bone_writer.hpp"

#include "dqskin/error.hpp"
#include "../write/vertex_sharing.hpp"

#include <cassert>
#include <filesystem>

namespace dqskin {

std::vector<VatSource> vat_sources(const Asset& asset, const std::vector<MeshInstance>& instances) {
  std::vector<VatSource> sources;
  for (const MeshInstance& inst : instances) {
    const Mesh& mesh = asset.meshes[size_t(inst.mesh)];
    const std::vector<size_t> owners = vertex_data_owners(mesh);
    std::vector<size_t> source_of(owners.size());
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      if (owners[p] != p) {
        sources[source_of[owners[p]]].shared_by.push_back(int(p));
        continue;
      }
      source_of[p] = sources.size();
      sources.push_back({inst.node, inst.mesh, int(p), mesh.primitives[p].vertex_count(),
                         asset.nodes[size_t(inst.node)].name, mesh.name, {}});
    }
  }
  return sources;
}

std::vector<Committed> write_bone_texture(const std::string& exr_path, const std::string& json_path,
                                          const BoneTexture& texture, const Asset& asset, int skin,
                                          std::span<const double> times, double fps, const CommitOptions& options) {
  assert(skin >= 0 && size_t(skin) < asset.skins.size());
  assert(times.size() == texture.frames);
  assert(texture.rgba.size() == texture.frames * texture.width() * 4);
  BoneImage image;
  image.profile = BoneProfile::kDq;
  image.width = texture.width();
  image.height = texture.frames;
  image.joints = texture.joints;
  image.frames = texture.frames;
  image.texels_per_joint = texture.texels_per_joint;
  image.rgba = texture.rgba;
  texture::BoneTextureWriter writer(exr_path, json_path, std::move(image), texture::TexelType::kFloat32, asset, skin,
                                    times, fps);
  std::vector<Committed> committed = writer.commit(nullptr, options);
  // A caller of this one writer gets what the bake gets by syncing once: files on disk before we return.
  sync_folder(std::filesystem::path(exr_path).parent_path().string());
  return committed;
}

}  // namespace dqskin
