// Bone textures as OpenEXR files with JSON side files (shared/DESIGN.md "BoneTexture layout"), and the
// vertex order of vertex-animation textures.
#include "dqskin/texture_output.hpp"
#include "../texture/texel_image.hpp"

#include "dqskin/error.hpp"

#include <nlohmann/json.hpp>

#include <cassert>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace dqskin {
namespace {

using Json = nlohmann::ordered_json;  // keys in the order written, for people reading the side files

// A side file: written by name to its AtomicFile's temporary (handed over at once, like the images, so
// that all outputs are committed the same way).
class TextFile {
public:
  explicit TextFile(std::string path) : file_(std::move(path)), temporary_(file_.hand_over()) {}

  void write(const std::string& text) {
    std::ofstream out(temporary_, std::ios::binary | std::ios::trunc);
    out.write(text.data(), std::streamsize(text.size()));
    out.close();
    if (!out) throw OutputError(file_.path() + ": cannot write");
  }

  AtomicFile& file() { return file_; }
  const std::string& temporary() const { return temporary_; }

private:
  AtomicFile file_;
  std::string temporary_;
};


// Commits the files in order. Under kRefuseDifferent they are all compared first, so that a refusal leaves
// every final name as it was (AtomicFile alone would refuse file by file, after renaming the earlier ones).
std::vector<Committed> commit_all(const std::vector<AtomicFile*>& files, const CommitOptions& options) {
  if (options.overwrite == Overwrite::kRefuseDifferent)
    for (const AtomicFile* f : files)
      if (f->conflicts()) throw OutputError(f->path() + ": exists with different contents; not overwritten");
  std::vector<Committed> result;
  for (AtomicFile* f : files) result.push_back(f->commit(options));
  return result;
}

// How the side file names a file: relative to the side file's folder, so the outputs can move together.
std::string name_from(const std::string& json_path, const std::string& path) {
  namespace fs = std::filesystem;
  return fs::path(path).lexically_proximate(fs::path(json_path).parent_path()).generic_string();
}

Json fps_json(double fps) { return fps > 0 ? Json(fps) : Json(nullptr); }

// Node and mesh names come from the file: invalid UTF-8 is replaced rather than refused.
std::string dump(const Json& json) { return json.dump(2, ' ', false, Json::error_handler_t::replace) + "\n"; }

}  // namespace

std::vector<VatSource> vat_sources(const Asset& asset, const std::vector<MeshInstance>& instances) {
  std::vector<VatSource> sources;
  for (const MeshInstance& inst : instances) {
    const Mesh& mesh = asset.meshes[size_t(inst.mesh)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      sources.push_back({inst.node, inst.mesh, int(p), mesh.primitives[p].vertex_count(),
                         asset.nodes[size_t(inst.node)].name, mesh.name});
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
  const Skin& s = asset.skins[size_t(skin)];
  if (texture.width() == 0 || texture.frames == 0)
    throw InputError(exr_path + ": a bone texture needs at least one joint and one frame");

  AtomicFile image(exr_path);
  texture::TexelFileWriter writer(image, texture::TexelType::kFloat32, texture.width(), texture.frames, 4);
  texture::TexelImage rows(texture::TexelType::kFloat32, texture.width(), texture.frames, 4);
  std::memcpy(rows.data(), texture.rgba.data(), texture.rgba.size() * sizeof(float));
  writer.write(rows);
  writer.close();
  TextFile json(json_path);

  Json doc;
  doc["format"] = "dqskin bone texture";
  doc["version"] = 1;
  doc["skin"] = skin;
  doc["skin_name"] = s.name;
  Json names = Json::array();
  for (int j : s.joints) names.push_back(asset.nodes[size_t(j)].name);
  doc["joints"] = std::move(names);
  doc["joint_nodes"] = s.joints;
  doc["texels_per_joint"] = texture.texels_per_joint;
  doc["frame_count"] = texture.frames;
  doc["fps"] = fps_json(fps);
  doc["frame_times"] = std::vector<double>(times.begin(), times.end());
  doc["width"] = texture.width();
  doc["height"] = texture.frames;
  doc["texel"] = texture.texels_per_joint == 5
                     ? "component k of joint j at frame f is at (5 * j + k, f): k = 0 real, 1 dual (x, y, z, w; "
                       "w scalar), 2..4 rows of the scale/shear S in xyz with w = 0"
                     : "component k of joint j at frame f is at (2 * j + k, f): k = 0 real, 1 dual (x, y, z, w; "
                       "w scalar)";
  doc["file"] = name_from(json_path, exr_path);
  doc["channels"] = "RGBA";
  doc["type"] = "float32";
  json.write(dump(doc));

  return commit_all({&image, &json.file()}, options);
}

}  // namespace dqskin
