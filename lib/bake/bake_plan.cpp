#include "bake_plan.hpp"
#include "morph_bake.hpp"
#include "vat_bake.hpp"
#include "../texture/vat_writer.hpp"
#include "../write/glb_appearance.hpp"

namespace dqskin::bake_detail {

size_t TextureClips::frames() const {
  size_t n = 0;
  for (const ClipPlan* c : clips) n += c->times.size();
  return n;
}

TextureClips clip_texture_set(const ClipPlan& clip) {
  TextureClips set{{&clip}, clip.folder, "clip " + clip.name, clip.has_texture_frames()};
  if (set.mine && !clip.whole_textures()) {
    set.first = clip.texture_first;
    set.end = clip.texture_end;
    set.head = clip.clip_mine;
  }
  return set;
}

std::vector<TextureClips> texture_clip_sets(const InputPlan& input, bool combine) {
  std::vector<TextureClips> sets;
  if (!combine) {
    for (const ClipPlan& clip : input.clips) sets.push_back(clip_texture_set(clip));
    return sets;
  }
  if (input.clips.empty()) return sets;
  TextureClips all{{}, input.stem, "", input.clips.front().clip_mine};
  std::string names;
  for (const ClipPlan& clip : input.clips) {
    all.clips.push_back(&clip);
    names += (names.empty() ? "" : ", ") + clip.name;
  }
  all.what = (all.clips.size() == 1 ? "clip " : "clips ") + names;
  sets.push_back(std::move(all));
  return sets;
}

unsigned per_clip_formats(const BakeOptions& options) {
  if (!options.textures.combine_clips) return options.formats;
  return options.formats & ~(unsigned(BakeFormat::kVat) | unsigned(BakeFormat::kBones));
}

std::vector<size_t> frames_to_deform(const ClipPlan& clip, unsigned formats) {
  const bool morph = clip.morph_mine && (formats & unsigned(BakeFormat::kMorph));
  const bool vat = clip.has_texture_frames() && (formats & unsigned(BakeFormat::kVat));
  const bool per_frame = formats & (unsigned(BakeFormat::kGlb) | unsigned(BakeFormat::kPly) | unsigned(BakeFormat::kObj));
  auto texture_frame = [&](size_t f) {
    return (f >= clip.texture_first && f < clip.texture_end) || (f == 0 && clip.texture_first > 0) || f == clip.texture_end;
  };
  std::vector<size_t> out;
  for (size_t f = 0; f < clip.times.size(); ++f)
    if (morph || (vat && texture_frame(f)) || (per_frame && clip.frame_mine[f])) out.push_back(f);
  return out;
}

std::vector<double> frames_and_midpoints(const std::vector<double>& t) {
  std::vector<double> out;
  for (size_t f = 0; f < t.size(); ++f) {
    out.push_back(t[f]);
    if (f + 1 < t.size()) out.push_back(t[f] + (t[f + 1] - t[f]) / 2);
  }
  return out;
}

std::vector<std::string> planned_files(const InputPlan& input, const ClipPlan& clip, const BakeOptions& options) {
  const unsigned formats = options.formats;
  std::vector<std::string> files;
  const struct {
    BakeFormat format;
    const char* extension;
  } per_frame[] = {{BakeFormat::kGlb, "glb"}, {BakeFormat::kPly, "ply"}, {BakeFormat::kObj, "obj"}};
  for (const auto& [format, extension] : per_frame)
    if (formats & unsigned(format))
      for (size_t f = 0; f < clip.times.size(); ++f)
        if (clip.frame_mine[f]) files.push_back(clip.frame_file(f, extension));
  if (!options.textures.combine_clips) {
    const std::vector<std::string> textures = planned_texture_files(input, clip_texture_set(clip), options);
    files.insert(files.end(), textures.begin(), textures.end());
  }
  if ((formats & unsigned(BakeFormat::kMorph)) && clip.morph_mine) files.push_back(morph_file(clip));
  if (!clip.clip_mine) return files;
  if ((formats & unsigned(BakeFormat::kGlb)) && options.glb_images == GlbImages::kShared)
    for (size_t i = 0; i < input.asset->images.size(); ++i)
      if (std::string name = glb::shared_image_name(input.asset->images[i], i); !name.empty())
        files.push_back(clip.folder + "/" + name);
  if ((formats & unsigned(BakeFormat::kObj)) && !input.asset->materials.empty())
    files.push_back(clip.folder + "/materials.mtl");
  return files;
}

std::vector<std::string> planned_texture_files(const InputPlan& input, const TextureClips& set, const BakeOptions& options) {
  std::vector<std::string> files;
  if (!set.mine) return files;
  if (options.formats & unsigned(BakeFormat::kVat))
    for (auto& [name, size] : planned_vat_files(input, set, options.textures)) files.push_back(std::move(name));
  if ((options.formats & unsigned(BakeFormat::kBones)) && !input.skins.empty() && set.head) {
    files.push_back(set.folder + "/" + kBonesMeshFile);
    // A slice's checked texture: its JSON as a template the merge fills with every slice's figures.
    const bool to_fill = set.sliced() && options.textures.check;
    for (int skin : input.skins) {
      const std::string base = set.folder + "/bones_skin" + std::to_string(skin);
      files.push_back(base + ".exr");
      files.push_back(to_fill ? texture::template_file_name(base + ".json") : base + ".json");
    }
  }
  return files;
}

}  // namespace dqskin::bake_detail
