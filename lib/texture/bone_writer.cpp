#include "bone_writer.hpp"

#include "texel_image.hpp"

#include "dqskin/error.hpp"

#include <nlohmann/json.hpp>

#include <cassert>
#include <cmath>
#include <filesystem>
#include <optional>

namespace dqskin::texture {

using Json = nlohmann::ordered_json;  // keys in the order written, for people reading the side files

struct BoneTextureWriter::Impl {
  AtomicFile image;
  AtomicFile json;
  BoneImage texture;
  TexelType type;
  std::string temporary;
  const Asset& asset;
  int skin;
  std::vector<double> times;
  double fps;

  Impl(const std::string& exr_path, const std::string& json_path, BoneImage t, TexelType tt, const Asset& a, int s,
       std::span<const double> ts, double f)
      : image(exr_path, false), json(json_path, false), texture(std::move(t)), type(tt), asset(a), skin(s),
        times(ts.begin(), ts.end()), fps(f) {}
};

BoneTextureWriter::BoneTextureWriter(const std::string& exr_path, const std::string& json_path, BoneImage image,
                                     TexelType type, const Asset& asset, int skin, std::span<const double> times,
                                     double fps, const std::string& compression)
    : impl_(std::make_unique<Impl>(exr_path, json_path, std::move(image), type, asset, skin, times, fps)) {
  Impl& m = *impl_;
  assert(type == TexelType::kFloat32 || type == TexelType::kHalf);
  assert(skin >= 0 && size_t(skin) < asset.skins.size());
  if (m.texture.width == 0 || m.texture.height == 0)
    throw InputError(exr_path + ": a bone texture needs at least one joint and one frame");
  TexelImage rows(type, m.texture.width, m.texture.height, 4);
  for (size_t y = 0; y < m.texture.height; ++y)
    for (size_t x = 0; x < m.texture.width; ++x)
      for (int c = 0; c < 4; ++c) {
        float value = m.texture.rgba[(y * m.texture.width + x) * 4 + size_t(c)];
        if (!std::isfinite(value))
          throw InputError(exr_path + ": texel (" + std::to_string(x) + ", " + std::to_string(y) + ") is not finite");
        if (type == TexelType::kHalf && !to_half(value, value))
          throw InputError(exr_path + ": texel (" + std::to_string(x) + ", " + std::to_string(y) + ") holds " +
                           std::to_string(m.texture.rgba[(y * m.texture.width + x) * 4 + size_t(c)]) +
                           ", beyond half precision (largest 65504); use --encoding float");
        rows.set(x, y, c, value);
      }
  TexelFileWriter writer(m.image, type, m.texture.width, m.texture.height, 4, compression);
  writer.write(rows);
  writer.close();
  m.temporary = writer.temporary();
}

BoneTextureWriter::~BoneTextureWriter() = default;

BoneImage BoneTextureWriter::read_back() const {
  const Impl& m = *impl_;
  TexelFileReader reader(m.temporary, m.image.path(), m.type, m.texture.width, m.texture.height, 4);
  TexelImage rows;
  reader.read(0, m.texture.height, rows);
  if (const std::string at = rows.first_non_finite(); !at.empty())
    throw OutputError(m.image.path() + ": texel " + at + " is not finite");
  BoneImage back = m.texture;
  for (size_t y = 0; y < back.height; ++y)
    for (size_t x = 0; x < back.width; ++x)
      for (int c = 0; c < 4; ++c) back.rgba[(y * back.width + x) * 4 + size_t(c)] = rows.get(x, y, c);
  return back;
}

std::vector<Committed> BoneTextureWriter::commit(const DecodeCheck* check, const CommitOptions& options,
                                                const std::vector<VatClipEntry>& clips,
                                                const std::vector<DecodeCheck>& clip_checks) {
  Impl& m = *impl_;
  const BoneImage& t = m.texture;
  const Skin& s = m.asset.skins[size_t(m.skin)];
  Json doc;
  doc["format"] = "dqskin bone texture";
  doc["version"] = 2;
  doc["profile"] = to_string(t.profile);
  doc["blend"] = implied_blend(t.profile);
  doc["skin"] = m.skin;
  doc["skin_name"] = s.name;
  Json names = Json::array();
  for (int j : s.joints) names.push_back(m.asset.nodes[size_t(j)].name);
  doc["joints"] = std::move(names);
  doc["joint_nodes"] = s.joints;
  doc["texels_per_joint"] = t.texels_per_joint;
  doc["frame_count"] = t.frames;
  doc["fps"] = m.fps > 0 ? Json(m.fps) : Json(nullptr);
  doc["frame_times"] = m.times;
  // The clip table (when the caller names the clips): row r is frame r, so a clip's rows are its frames;
  // mat4 stores its frames bottom-up (bone_profiles.cpp), so there a clip's top row is its last frame's.
  if (!clips.empty()) {
    Json table = Json::array();
    for (size_t i = 0; i < clips.size(); ++i) {
      const VatClipEntry& c = clips[i];
      const size_t first_row =
          t.profile == BoneProfile::kMat4 ? t.frames - c.first_frame - c.frame_count : c.first_frame;
      Json entry = {{"name", c.name},
                    {"first_row", first_row},
                    {"row_count", c.frame_count},
                    {"first_frame", c.first_frame},
                    {"frame_count", c.frame_count},
                    {"fps", c.fps > 0 ? Json(c.fps) : Json(nullptr)},
                    {"duration", c.duration},
                    {"loop", c.loops}};
      if (i < clip_checks.size()) entry["decode_check"] = clip_checks[i].to_json();
      table.push_back(std::move(entry));
    }
    doc["clips"] = std::move(table);
  }
  doc["width"] = t.width;
  doc["height"] = t.height;
  if (t.profile == BoneProfile::kDq)  // version 1's wording, kept for its readers
    doc["texel"] = t.texels_per_joint == 5
                       ? "component k of joint j at frame f is at (5 * j + k, f): k = 0 real, 1 dual (x, y, z, w; "
                         "w scalar), 2..4 rows of the scale/shear S in xyz with w = 0"
                       : "component k of joint j at frame f is at (2 * j + k, f): k = 0 real, 1 dual (x, y, z, w; "
                         "w scalar)";
  else
    doc["texel"] = texel_formula(t.profile);
  doc["decode"] = decode_formula(t.profile);
  namespace fs = std::filesystem;
  doc["file"] = fs::path(m.image.path()).lexically_proximate(fs::path(m.json.path()).parent_path()).generic_string();
  doc["channels"] = "RGBA";
  doc["type"] = m.type == TexelType::kHalf ? "float16" : "float32";
  if (check) doc["decode_check"] = check->to_json();
  m.json.write(doc.dump(2, ' ', false, Json::error_handler_t::replace) + "\n");

  if (options.overwrite == Overwrite::kRefuseDifferent)
    for (const AtomicFile* f : {&m.image, &m.json})
      if (f->conflicts()) throw OutputError(f->path() + ": exists with different contents; not overwritten");
  return {m.image.commit(options), m.json.commit(options)};
}

}  // namespace dqskin::texture
