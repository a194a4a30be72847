#include "bake_work.hpp"
#include "morph_bake.hpp"
#include "vat_bake.hpp"

#include "../write/mesh_output.hpp"
#include "../texture/texture_output.hpp"
#include "../base/file_kind.hpp"
#include "../write/glb_appearance.hpp"
#include "../base/byte_size.hpp"
#include "../base/saturating.hpp"
#include "../texture/bone_profiles.hpp"
#include "dqskin/error.hpp"

#include <sys/stat.h>
#include <sys/statvfs.h>

#include <algorithm>
#include <optional>

namespace dqskin::bake_detail {
namespace {

using saturating::add;
using saturating::mul;

bool ends_with(const std::string& s, const char* suffix) { return s.ends_with(suffix); }

// The rest pose of every instance as one frame, in the writers' layout: the right counts for a size.
DeformedBatch rest_frame(const Asset& asset, const std::vector<MeshInstance>& instances) {
  DeformedBatch batch;
  batch.frame_count = 1;
  for (const MeshInstance& inst : instances)
    for (const Primitive& p : asset.meshes[size_t(inst.mesh)].primitives) {
      DeformedBatch::Primitive out;
      out.vertices = p.vertex_count();
      for (const glm::vec3& v : p.positions) out.positions.insert(out.positions.end(), {v.x, v.y, v.z});
      for (const glm::vec3& n : p.normals) out.normals.insert(out.normals.end(), {n.x, n.y, n.z});
      for (const glm::vec4& t : p.tangents) out.tangents.insert(out.tangents.end(), {t.x, t.y, t.z, t.w});
      batch.primitives.push_back(std::move(out));
    }
  return batch;
}

// Uncompressed RGBA32F EXR of width × height, with its header and line offsets.
uint64_t exr_bytes(uint64_t width, uint64_t height) { return add(mul(mul(width, height), 16), 1024 + height / 16 * 8); }

}  // namespace

BakeWork& BakeWork::operator+=(const BakeWork& o) {
  vertex_frames = add(vertex_frames, o.vertex_frames);
  bytes = add(bytes, o.bytes);
  existing = add(existing, o.existing);
  files += o.files;
  return *this;
}

BakeWork estimate_work(const InputPlan& input, const BakeOptions& options, const GlbWriter* glb) {
  const Asset& asset = *input.asset;
  uint64_t vertices = 0;
  for (const MeshInstance& inst : input.instances)
    for (const Primitive& p : asset.meshes[size_t(inst.mesh)].primitives) vertices += p.vertex_count();

  // One frame of each per-frame format, encoded from the rest pose.
  uint64_t glb_frame = 0, ply_frame = 0, obj_frame = 0;
  if (options.formats & (unsigned(BakeFormat::kGlb) | unsigned(BakeFormat::kPly) | unsigned(BakeFormat::kObj))) {
    const DeformedBatch rest = rest_frame(asset, input.instances);
    const FrameView view = frame_view(rest, 0);
    if (glb) glb_frame = glb->encode(view, nullptr, 0.0).size();
    if (options.formats & (unsigned(BakeFormat::kPly) | unsigned(BakeFormat::kObj))) {
      const MergedMesh mesh = merge_frame(asset, input.instances, view);
      if (options.formats & unsigned(BakeFormat::kPly)) ply_frame = encode_ply(mesh).size();
      if (options.formats & unsigned(BakeFormat::kObj)) obj_frame = encode_obj(mesh, asset, "materials.mtl").size();
    }
  }

  // The glb frames' shared images, by file name (bake_plan.cpp names them the same way).
  std::vector<std::pair<std::string, uint64_t>> images;
  for (size_t i = 0; i < asset.images.size(); ++i)
    if (std::string name = glb::shared_image_name(asset.images[i], i); !name.empty())
      images.emplace_back(std::move(name), asset.images[i].bytes.size());

  BakeWork work;
  // A texture file's size: the VAT planner's bound, or a bone texture's.
  auto texture_bytes = [&](const std::string& file, const TextureClips& set,
                           const std::vector<std::pair<std::string, uint64_t>>& vat) -> std::optional<uint64_t> {
    const auto in_vat = std::find_if(vat.begin(), vat.end(), [&](const auto& v) { return v.first == file; });
    if (in_vat != vat.end()) return in_vat->second;
    if (file.find("/bones_skin") == std::string::npos) return std::nullopt;
    const uint64_t frames = set.frames();
    const size_t skin = std::stoul(file.substr(file.rfind("bones_skin") + 10));
    const uint64_t joints = asset.skins[skin].joints.size();
    // Refused before anything is written: the smallest image the profile packs (dq's rigid joints take
    // 2 texels, bones_bake checks the packed one) already past --max-size.
    BoneProfile profile{};
    if (ends_with(file, ".exr") && parse_bone_profile(options.textures.bones_profile, profile))
      if (const std::string why = bone_size_problem(profile, bone_image_size(profile, joints, frames), options.textures.max_size);
          !why.empty())
        throw InputError(set.what + ": skin " + std::to_string(skin) + ": " + why);
    return ends_with(file, ".exr") ? exr_bytes(mul(joints, 5), frames) : add(1024, add(mul(joints, 48), mul(frames, 24)));
  };
  // Any other file's: a frame's, the material library's, a texture's (the meshes beside textures are
  // counted as a glb frame).
  auto other_bytes = [&](const std::string& file, const TextureClips& set,
                         const std::vector<std::pair<std::string, uint64_t>>& vat) -> uint64_t {
    if (ends_with(file, ".glb")) return glb_frame;
    if (ends_with(file, ".ply")) return ply_frame;
    if (ends_with(file, ".obj")) return obj_frame;
    if (ends_with(file, "materials.mtl")) return encode_mtl(asset).size();
    return texture_bytes(file, set, vat).value_or(0);
  };
  auto count = [&](const std::string& file, uint64_t size) {
    work.bytes = add(work.bytes, add(size, 160));  // and its line in the manifest
    ++work.files;
    struct stat st {};
    if (::stat((options.plan.out_dir + "/" + file).c_str(), &st) == 0 && S_ISREG(st.st_mode))
      work.existing = add(work.existing, uint64_t(st.st_size));
  };
  const bool combine = options.textures.combine_clips;
  for (const ClipPlan& clip : input.clips) {
    // The morph animation holds every frame until its keys are chosen: past --max-memory it cannot be
    // made, which is known before anything else of the bake is done.
    if ((options.formats & unsigned(BakeFormat::kMorph)) && clip.morph_mine)
      if (const uint64_t held = morph_frames_bytes(input, clip); held > options.plan.load.max_memory)
        throw InputError("clip " + clip.name + ": the morph animation holds every frame, " +
                         std::to_string(clip.times.size()) + " frames of " + std::to_string(held / clip.times.size() / 24) +
                         " vertices in " + byte_size(held) + ", more than --max-memory " +
                         byte_size(options.plan.load.max_memory) + " (fewer frames, with --fps or --frames, would fit)");
    work.vertex_frames = add(work.vertex_frames, mul(vertices, frames_to_deform(clip, per_clip_formats(options)).size()));
    const TextureClips one = clip_texture_set(clip);  // this shard's slice, whose pieces planned_files lists
    std::vector<std::pair<std::string, uint64_t>> vat;
    if ((options.formats & unsigned(BakeFormat::kVat)) && !combine) vat = planned_vat_files(input, one, options.textures);
    for (const std::string& file : planned_files(input, clip, options)) {
      uint64_t size = 0;
      const auto image =
          std::find_if(images.begin(), images.end(), [&](const auto& i) { return file == clip.folder + "/" + i.first; });
      if (file == morph_file(clip)) size = planned_morph_bytes(input, clip);
      else if (image != images.end()) size = image->second;
      else size = other_bytes(file, one, vat);
      count(file, size);
    }
  }
  // With --combine-clips, the textures of every clip at once, from their own pass.
  if (combine)
    for (const TextureClips& set : texture_clip_sets(input, true)) {
      if (!set.mine) continue;
      std::vector<std::pair<std::string, uint64_t>> vat;
      if (options.formats & unsigned(BakeFormat::kVat)) {
        vat = planned_vat_files(input, set, options.textures);
        work.vertex_frames = add(work.vertex_frames, mul(vertices, set.frames()));
      }
      for (const std::string& file : planned_texture_files(input, set, options))
        count(file, other_bytes(file, set, vat));
    }
  return work;
}

uint64_t free_bytes(const std::string& folder) {
  struct statvfs fs {};
  if (::statvfs(nearest_existing(folder).c_str(), &fs) != 0) return saturating::kMax;  // unknown: do not refuse
  return mul(fs.f_bavail, fs.f_frsize);
}

}  // namespace dqskin::bake_detail
