#include "bones_bake.hpp"

#include "../base/parallel_for.hpp"
#include "../base/length_text.hpp"
#include "../texture/bone_writer.hpp"
#include "../texture/bones_mesh_glb.hpp"
#include "../texture/vat_check.hpp"
#include "../texture/vat_codec.hpp"
#include "../texture/vat_writer.hpp"

#include "dqskin/error.hpp"
#include "dqskin/frame_view.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>

namespace dqskin::bake_detail {


using texture::ErrorHistogram;

namespace {


texture::TexelType bone_texel_type(const TextureOptions& o) {
  // Bone textures are float or half; the PNG encodings are the VAT's (docs/formats.md, "Encodings").
  return o.encoding == "half" ? texture::TexelType::kHalf : texture::TexelType::kFloat32;
}

// A primitive of an instance drawn with the skin being checked, and where its vertices are in a frame.
struct SkinnedPrimitive {
  size_t instance = 0, primitive = 0;  // the instance's index and the primitive's in its mesh
  size_t view = 0;                     // its index in a FrameView
};

// What the check of one texture accumulates.
struct SkinCheck {
  ErrorHistogram frames, midpoints;
  double normal_degrees = 0, midpoint_normal_degrees = 0;
  double reference_motion = 0, decoded_motion = 0;
  texture::Box bounds;  // of the deformed vertices over the clip, for a relative --max-error
  std::vector<std::vector<glm::dvec3>> first_decoded, first_reference;  // per skinned primitive, frame 0
};

// Compares one primitive at one time: each vertex skinned from `image` at `frame` against `reference`.
// Vertices are split among threads; their figures are merged afterwards.
// `baseline`: the clip's first frame before a slice that starts later, kept to measure motion from and
// not compared.
void compare_primitive(const Asset& asset, const MeshInstance& instance, size_t prim_index, const Pose& pose,
                       const BoneImage& image, size_t frame, const PrimitiveView& reference, bool midpoint,
                       bool first, bool baseline, size_t skinned, SkinCheck& check, unsigned threads) {
  const Primitive& prim = asset.meshes[size_t(instance.mesh)].primitives[prim_index];
  const size_t n = prim.vertex_count();
  const std::vector<double>& morph = pose.weights[size_t(instance.node)];
  const size_t chunk = 4096, chunks = (n + chunk - 1) / chunk;
  struct Partial {
    ErrorHistogram errors;
    double degrees = 0, reference_motion = 0, decoded_motion = 0;
    texture::Box bounds;
  };
  std::vector<Partial> partial(chunks);
  // `first`: the clip's first frame, which the motion is measured from.
  if (first) {
    check.first_decoded.resize(std::max(check.first_decoded.size(), skinned + 1));
    check.first_reference.resize(std::max(check.first_reference.size(), skinned + 1));
    check.first_decoded[skinned].resize(n);
    check.first_reference[skinned].resize(n);
  }
  concurrency::parallel_for(chunks, threads, [&](size_t c) {
    Partial& out = partial[c];
    const size_t per = size_t(prim.influences);
    for (size_t v = c * chunk; v < std::min(n, (c + 1) * chunk); ++v) {
      // Morph targets first (glTF 2.0 §3.7.3), as the runtime does before its skinning.
      glm::dvec3 p(prim.positions[v]);
      glm::dvec3 nrm = prim.normals.empty() ? glm::dvec3(0.0) : glm::dvec3(prim.normals[v]);
      for (size_t k = 0; k < morph.size() && k < prim.targets.size(); ++k) {
        if (morph[k] == 0) continue;
        if (!prim.targets[k].positions.empty()) p += morph[k] * glm::dvec3(prim.targets[k].positions[v]);
        if (!prim.normals.empty() && !prim.targets[k].normals.empty())
          nrm += morph[k] * glm::dvec3(prim.targets[k].normals[v]);
      }
      std::array<int, kMaxInfluences> joints{};  // every JOINTS_n set the loader reads (asset.hpp)
      for (size_t i = 0; i < per; ++i) joints[i] = prim.joints[v * per + i];
      const std::span<const float> weights(&prim.weights[v * per], per);
      const SkinnedVertex s = skin_vertex(image, frame, std::span<const int>(joints.data(), per), weights, p, nrm);
      const glm::dvec3 want(reference.positions[3 * v], reference.positions[3 * v + 1], reference.positions[3 * v + 2]);
      if (baseline) {
        check.first_decoded[skinned][v] = s.position;
        check.first_reference[skinned][v] = want;
        continue;
      }
      out.errors.add(glm::length(s.position - want));
      out.bounds.add(want);
      if (first) {
        check.first_decoded[skinned][v] = s.position;
        check.first_reference[skinned][v] = want;
      } else if (!midpoint) {
        out.decoded_motion = std::max(out.decoded_motion, glm::length(s.position - check.first_decoded[skinned][v]));
        out.reference_motion = std::max(out.reference_motion, glm::length(want - check.first_reference[skinned][v]));
      }
      if (reference.normals.empty() || prim.normals.empty()) continue;
      const glm::dvec3 wn(reference.normals[3 * v], reference.normals[3 * v + 1], reference.normals[3 * v + 2]);
      const double l = glm::length(wn) * glm::length(s.normal);
      if (!(l > 0)) continue;
      const double cosine = std::clamp(glm::dot(wn, s.normal) / l, -1.0, 1.0);
      out.degrees = std::max(out.degrees, std::acos(cosine) * 180 / std::numbers::pi);
    }
  });
  for (const Partial& part : partial) {
    (midpoint ? check.midpoints : check.frames).merge(part.errors);
    double& degrees = midpoint ? check.midpoint_normal_degrees : check.normal_degrees;
    degrees = std::max(degrees, part.degrees);
    check.reference_motion = std::max(check.reference_motion, part.reference_motion);
    check.decoded_motion = std::max(check.decoded_motion, part.decoded_motion);
    check.bounds.add(part.bounds);
  }
}

}  // namespace

namespace {

// Whether a clip's last joint matrices are its first (to a millionth of the largest translation, float noise
// aside): the clip loops.
bool loops(const std::vector<JointTransforms>& frames, size_t first, size_t count) {
  if (count < 2) return false;
  const JointTransforms &a = frames[first], &b = frames[first + count - 1];
  double scale = 1, gap = 0;
  for (size_t j = 0; j < a.matrices.size(); ++j)
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) {
        scale = std::max(scale, std::abs(a.matrices[j][c][r]));
        gap = std::max(gap, std::abs(a.matrices[j][c][r] - b.matrices[j][c][r]));
      }
  return gap <= 1e-6 * scale;
}

texture::DecodeCheck figures(const SkinCheck& c) {
  texture::DecodeCheck d;
  d.max_error = c.frames.max();
  d.p99_error = c.frames.quantile(0.99);
  d.max_midpoint_error = c.midpoints.max();
  d.p99_midpoint_error = c.midpoints.quantile(0.99);
  d.max_normal_degrees = c.normal_degrees;
  d.max_midpoint_normal_degrees = c.midpoint_normal_degrees;
  d.samples = c.frames.count() + c.midpoints.count();
  return d;
}

}  // namespace

BonesClipResult bake_bones_clip(Deformer* deformer, const InputPlan& input, const TextureClips& set,
                                const BakeOptions& options, const CommitOptions& commit, unsigned threads,
                                const glb::Appearance* look) {
  const Asset& asset = *input.asset;
  const TextureOptions& o = options.textures;
  BoneProfile profile{};
  if (!parse_bone_profile(o.bones_profile, profile))
    throw InputError("--bones-profile '" + o.bones_profile + "' is not one of dq, dq-cocos, mat3x4, mat4");
  // Every clip's frames, one after another: row r of a texture is frame r (docs/DESIGN.md §4.9).
  std::vector<Pose> poses;
  std::vector<double> times;
  std::vector<texture::VatClipEntry> table;
  for (const ClipPlan* clip : set.clips) {
    const std::vector<double>& t = clip->times;
    table.push_back({clip->name, poses.size(), t.size(), clip->fps, t.empty() ? 0 : t.back() - t.front(), false});
    for (double time : t) {
      poses.push_back(sample_pose(asset, clip->clip, time));
      times.push_back(time);
    }
  }
  const double fps = std::all_of(table.begin(), table.end(), [&](const auto& c) { return c.fps == table.front().fps; })
                         ? table.front().fps
                         : 0.0;

  BonesClipResult result;
  std::vector<std::unique_ptr<texture::BoneTextureWriter>> writers;
  std::vector<std::string> bases, jsons;
  std::vector<std::vector<texture::VatClipEntry>> tables;  // per skin: the clip table with its loops
  for (int skin : input.skins) {
    std::vector<JointTransforms> frames;
    for (const Pose& pose : poses) frames.push_back(joint_transforms(asset.skins[size_t(skin)], pose));
    tables.push_back(table);
    for (texture::VatClipEntry& c : tables.back()) c.loops = loops(frames, c.first_frame, c.frame_count);
    const std::string base = set.folder + "/bones_skin" + std::to_string(skin);
    BoneImage image = pack_bones(profile, frames);
    if (const std::string why = bone_size_problem(profile, {image.width, image.height}, o.max_size); !why.empty())
      throw InputError(set.what + ": skin " + std::to_string(skin) + ": " + why);
    // A slice's checked texture: the JSON as a template the merge fills with every slice's figures.
    const std::string json = set.sliced() && o.check ? texture::template_file_name(base + ".json") : base + ".json";
    writers.push_back(std::make_unique<texture::BoneTextureWriter>(
        options.plan.out_dir + "/" + base + ".exr", options.plan.out_dir + "/" + json, std::move(image),
        bone_texel_type(o), asset, skin, times, fps, o.exr_compression));
    bases.push_back(base);
    jsons.push_back(json);
  }

  std::vector<std::optional<texture::DecodeCheck>> figures_of(writers.size());
  std::vector<std::vector<texture::DecodeCheck>> clip_figures(writers.size());
  if (o.check && !writers.empty() && deformer) {
    std::vector<BoneImage> images;
    for (const auto& w : writers) images.push_back(w->read_back());
    std::vector<SkinCheck> whole(writers.size());
    for (size_t c = 0; c < set.clips.size(); ++c) {
      const ClipPlan& clip = *set.clips[c];
      const size_t first = table[c].first_frame;
      std::vector<SkinCheck> checks(writers.size());
      // Every frame, and between neighbours the midpoint (frame f at 2f, the midpoint after it at 2f + 1); a
      // slice's frames and the midpoints after them, and before them the clip's first frame to measure
      // motion from.
      const std::vector<double> all_times = frames_and_midpoints(clip.times);
      const size_t from = set.sliced() ? 2 * set.first : 0;
      const size_t to = set.sliced() ? std::min(2 * set.end, all_times.size()) : all_times.size();
      const size_t baseline = from > 0 ? 1 : 0;
      std::vector<double> clip_times;
      if (baseline) clip_times.push_back(all_times[0]);
      for (size_t i = from; i < to; ++i) clip_times.push_back(all_times[i]);
      deformer->run(clip.clip, clip_times, [&](const DeformedBatch& batch) {
        for (size_t k = 0; k < batch.frame_count; ++k) {
          const size_t at_batch = batch.first_frame + k;
          const bool only_baseline = at_batch < baseline;
          const size_t i = only_baseline ? 0 : from + at_batch - baseline;
          const bool midpoint = i % 2 == 1;
          // Morph weights: the frames' poses were sampled for packing; only midpoints need sampling.
          const Pose midpoint_pose = midpoint ? sample_pose(asset, clip.clip, all_times[i]) : Pose();
          const Pose& pose = midpoint ? midpoint_pose : poses[first + i / 2];
          const FrameView view = frame_view(batch, k);
          size_t at = 0;
          for (size_t s = 0; s < input.skins.size(); ++s) {
            size_t skinned = 0;
            at = 0;
            for (const MeshInstance& instance : input.instances) {
              const size_t primitives = asset.meshes[size_t(instance.mesh)].primitives.size();
              if (instance.skin == input.skins[s])
                for (size_t p = 0; p < primitives; ++p, ++skinned)
                  compare_primitive(asset, instance, p, pose, images[s], first + i / 2, view.primitives[at + p],
                                    midpoint, i == 0, only_baseline, skinned, checks[s], threads);
              at += primitives;
            }
          }
        }
      });
      for (size_t s = 0; s < writers.size(); ++s) {
        const SkinCheck& check = checks[s];
        const texture::DecodeCheck d = figures(check);
        const std::string what = "clip " + clip.name + ", bones_skin" + std::to_string(input.skins[s]);
        // Float noise aside: a millionth of the clip's size.
        if (check.reference_motion > 1e-6 * check.bounds.diagonal() && check.decoded_motion == 0)
          throw InputError(what + ": every frame of the texture skins to one pose while the clip moves " +
                           length_text(check.reference_motion));
        if (o.max_error > 0) {
          const double limit = o.max_error_relative ? o.max_error * check.bounds.diagonal() : o.max_error;
          if (d.max_error > limit)
            throw InputError(what + ": the texture skins (" + implied_blend(profile) + ") to within " +
                             length_text(d.max_error) + " of the deformed mesh (--mode " + to_string(options.mode) +
                             "), over --max-error " + length_text(limit));
        }
        clip_figures[s].push_back(d);
        result.checks.push_back(texture_check(d, input.path, clip.name, "bones_skin" + std::to_string(input.skins[s])));
        if (set.sliced()) {
          texture::DecodeShare share;
          share.frames = check.frames;
          share.midpoints = check.midpoints;
          share.max_normal_degrees = check.normal_degrees;
          share.max_midpoint_normal_degrees = check.midpoint_normal_degrees;
          nlohmann::json j = share.to_json();
          j["slice"] = {set.first, set.end};  // the merge checks that the slices cover the clip once
          result.checks.back().share = j.dump();
        }
        whole[s].frames.merge(check.frames);
        whole[s].midpoints.merge(check.midpoints);
        whole[s].normal_degrees = std::max(whole[s].normal_degrees, check.normal_degrees);
        whole[s].midpoint_normal_degrees = std::max(whole[s].midpoint_normal_degrees, check.midpoint_normal_degrees);
      }
    }
    for (size_t s = 0; s < writers.size(); ++s) figures_of[s] = figures(whole[s]);
  }
  // Only the head writes the files (a slice's other shards check their frames); their temporaries go.
  if (writers.empty() || !set.head) return result;
  // The skinned mesh the textures deform, first: a reader that finds a texture finds its mesh.
  const std::string mesh_name = set.folder + "/" + kBonesMeshFile;
  AtomicFile mesh(options.plan.out_dir + "/" + mesh_name, false);
  mesh.write(texture::encode_bones_mesh_glb(asset, input.instances, input.stem, look));
  if (commit.overwrite == Overwrite::kRefuseDifferent && mesh.conflicts())
    throw OutputError(mesh.path() + ": exists with different contents; not overwritten");
  result.files.emplace_back(mesh_name, mesh.commit(commit));
  for (size_t s = 0; s < writers.size(); ++s) {
    // One clip: the texture's figures are the clip's; several: each clip's too, in the clip table.
    const std::vector<texture::DecodeCheck> per_clip = set.clips.size() > 1 ? clip_figures[s] : std::vector<texture::DecodeCheck>();
    const bool to_fill = set.sliced() && figures_of[s];
    const std::vector<Committed> c =
        writers[s]->commit(figures_of[s] && !to_fill ? &*figures_of[s] : nullptr, commit, tables[s], per_clip);
    result.files.emplace_back(bases[s] + ".exr", c[0]);
    result.files.emplace_back(jsons[s], c[1]);
  }
  return result;
}

}  // namespace dqskin::bake_detail
