#include "vat_bake.hpp"

#include "../base/length_text.hpp"
#include "../texture/rest_glb.hpp"
#include "../texture/texel_image.hpp"
#include "../texture/vat_measure.hpp"
#include "vat_planner.hpp"
#include "dqskin/error.hpp"
#include "../texture/texture_output.hpp"
#include "../write/vertex_sharing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace dqskin::bake_detail {


using namespace texture;

TextureCheck texture_check(const texture::DecodeCheck& c, const std::string& input, const std::string& clip,
                           const std::string& texture) {
  return {input, clip, texture, c.max_error, c.p99_error, c.max_midpoint_error, c.p99_midpoint_error,
          c.max_normal_degrees, c.max_midpoint_normal_degrees, c.samples, {}};
}

namespace {

// One frame of a batch, kept after the deformer's sink returns.
DeformedBatch copy_frame(const DeformedBatch& batch, size_t k) {
  DeformedBatch one;
  one.frame_count = 1;
  for (const DeformedBatch::Primitive& p : batch.primitives) {
    DeformedBatch::Primitive q;
    q.vertices = p.vertices;
    auto slice = [&](const std::vector<float>& all, size_t per_vertex) {
      if (all.empty()) return std::vector<float>();
      const auto first = all.begin() + std::ptrdiff_t(k * p.vertices * per_vertex);
      return std::vector<float>(first, first + std::ptrdiff_t(p.vertices * per_vertex));
    };
    q.positions = slice(p.positions, 3);
    q.normals = slice(p.normals, 3);
    q.tangents = slice(p.tangents, 4);
    one.primitives.push_back(std::move(q));
  }
  return one;
}

VatFormat chosen_format(const TextureOptions& o) {
  VatProfile profile;
  if (!parse_vat_profile(o.vat_profile, profile))
    throw InputError("--vat-profile '" + o.vat_profile + "' is not one of dqskin, openvat, houdini");
  VatFormat f = default_format(profile);
  if (!o.encoding.empty() && !parse_texel_type(o.encoding, f.type))
    throw InputError("--encoding '" + o.encoding + "' is not one of float, half, png16, png8");
  if (!o.normals.empty() && !parse_normal_mode(o.normals, f.normals))
    throw InputError("--normals '" + o.normals + "' is not one of none, separate, packed, oct8, oct16");
  if (const std::string why = unsupported_reason(f); !why.empty()) throw InputError(why);
  if (!o.exr_compression.empty() && !is_lossless_exr_compression(o.exr_compression))
    throw InputError("--exr-compression '" + o.exr_compression + "' is not one of zip, piz, rle, zips, none (the lossless ones)");
  return f;
}
}  // namespace

VatFormat vat_format(const TextureOptions& options) { return chosen_format(options); }

std::optional<VatEncoding> sliceable_vat(const InputPlan& input, const ClipPlan& clip, const TextureOptions& options) {
  if (planner_active(options) || options.combine_clips) return std::nullopt;
  try {
    size_t vertices = 0;
    for (const VatSource& s : vat_sources(*input.asset, input.instances)) vertices += s.vertices;
    VatEncoding e;
    e.compression = options.exr_compression;
    e.layout = plan_vat_layout(chosen_format(options), vertices, clip.times.size(), options.max_size, options.pot, clip.name);
    if (vertices > 0 && sliceable(e)) return e;
  } catch (const InputError&) {
    // The profile cannot hold the clip: the whole texture's shard says so.
  }
  return std::nullopt;
}


std::vector<std::pair<std::string, uint64_t>> planned_vat_files(const InputPlan& input, const TextureClips& set,
                                                               const TextureOptions& options) {
  const VatFormat format = chosen_format(options);
  size_t vertices = 0, indices = 0;
  for (const VatSource& s : vat_sources(*input.asset, input.instances)) vertices += s.vertices;
  for (const MeshInstance& inst : input.instances)
    for (const Primitive& p : input.asset->meshes[size_t(inst.mesh)].primitives) indices += std::max(p.indices.size(), p.vertex_count());
  const std::string& what = set.what;
  if (vertices == 0) throw InputError(what + ": no vertices to bake into a vertex-animation texture");
  // With a budget the planner may keep fewer frames: the estimate takes the most that fit (an upper bound),
  // and leaves a clip that fits at no decimation to the planner's message.
  std::optional<VatLayout> fits;
  for (size_t step = 1; step <= (planner_active(options) ? 8u : 1u) && !fits; ++step) {
    size_t frames = 0;
    for (const ClipPlan* clip : set.clips) frames += (clip->times.size() - 1 + step - 1) / step + 1;
    try {
      fits = plan_vat_layout(format, vertices, frames, options.max_size, options.pot, what);
    } catch (const InputError&) {
      if (!planner_active(options)) throw;
    }
  }
  if (!fits) fits = plan_vat_layout(format, vertices, 1, 0, false, what);  // names only; the planner will refuse
  const VatLayout& l = *fits;
  VatEncoding e;
  e.layout = l;
  const VatFileNames names = vat_file_names(format, safe_name(input.stem));
  // Images at their uncompressed size plus a header and an EXR offset table (an upper bound: ZIP and PNG
  // store less); the rest mesh's attributes and indices; the JSON's per-frame lines.
  auto image = [&](TexelType type, int channels, size_t rows) {
    return uint64_t(l.width) * rows * uint64_t(channels) * channel_bytes(type) + 1024 + rows / 16 * 8;
  };
  std::vector<std::pair<std::string, uint64_t>> files;
  const std::string folder = set.folder + "/";
  for (size_t page = 0; page < l.pages; ++page) {
    // A slice's pieces of the page, or the page's images.
    const TexelRows rows = set.sliced() ? slice_page_rows(l, set.first, set.end, page) : TexelRows{0, l.page_height(page)};
    if (rows.end == 0) continue;
    auto name = [&](const std::string& whole) {
      const std::string n = page_file_name(whole, page, l.pages);
      return set.sliced() ? piece_file_name(n, rows.first, rows.end) : n;
    };
    files.emplace_back(folder + name(names.positions), image(format.type, l.position_channels(), rows.end - rows.first));
    if (const std::optional<TexelType> type = e.normal_image_type())
      files.emplace_back(folder + name(names.normals), image(*type, normal_channels(e), rows.end - rows.first));
  }
  if (!set.head) return files;
  // The rest mesh: its attributes (a third texture coordinate set at most) and indices, and the source's
  // images, which it embeds with the materials.
  uint64_t images = 0;
  for (const EncodedImage& i : input.asset->images) images += i.bytes.size() + 4;
  files.emplace_back(folder + names.rest_mesh,
                     4096 + uint64_t(vertices) * (12 + 12 + 8 + 8 + 8) + uint64_t(indices) * 4 + images);
  if (!names.profile_side_file.empty()) files.emplace_back(folder + names.profile_side_file, 4096 + set.clips.size() * 200);
  const std::string json = set.sliced() && options.check ? template_file_name(names.dqskin_side_file) : names.dqskin_side_file;
  files.emplace_back(folder + json, 8192 + uint64_t(set.frames()) * 200 + set.clips.size() * 400);
  return files;
}

VatClipBake::VatClipBake(Deformer& deformer, const InputPlan& input, TextureClips set, const BakeOptions& options,
                         const glb::Appearance* look)
    : set_(std::move(set)), options_(options), sharing_(shared_vertex_layout(*input.asset, input.instances)) {
  const TextureOptions& o = options.textures;
  const std::string& what = set_.what;
  VatEncoding e;
  e.compression = o.exr_compression;
  VatFormat format = chosen_format(o);
  const std::vector<VatSource> sources = vat_sources(*input.asset, input.instances);
  size_t vertices = 0;
  for (const VatSource& s : sources) vertices += s.vertices;
  if (vertices == 0) throw InputError(what + ": no vertices to bake into a vertex-animation texture");

  // The rest mesh: the rest pose (dqskin, openvat) or the clip's first frame (houdini, whose offsets start
  // there; it comes from the measuring pass).
  DeformedBatch rest;
  if (format.profile != VatProfile::kHoudini) {
    const double zero = 0;
    deformer.run(nullptr, std::span(&zero, 1), [&](const DeformedBatch& batch) { rest = copy_frame(batch, 0); });
    if (format.profile == VatProfile::kOpenVat) e.rest = all_positions(distinct_vertices(frame_view(rest, 0), sharing_));
  }

  // With a budget, the planner chooses the texel type and the frames.
  std::vector<double> fps;
  for (const ClipPlan* clip : set_.clips) {
    times_.push_back(clip->times);
    fps.push_back(clip->fps);
  }
  std::optional<VatChoice> planned;
  if (planner_active(o)) {
    const VatPlan plan = plan_vat(deformer, input, set_, o, e.rest);
    planned = plan.choices[plan.chosen];
    format.type = planned->format.type;
    times_ = plan.times;
    if (planned->step > 1) fps = plan.fps;
  }
  e.layout = plan_vat_layout(format, vertices, frames(), o.max_size, o.pot, what);

  // The measuring pass: bounds of what is stored, of each frame and of the clips; whether each loops.
  VatClipInfo info;
  info.asset = input.stem;
  info.clip = set_.clips.size() == 1 ? set_.clips.front()->name : std::string();
  info.fps = std::all_of(fps.begin(), fps.end(), [&](double f) { return f == fps.front(); }) ? fps.front() : 0.0;
  info.sources = sources;
  for (size_t c = 0; c < set_.clips.size(); ++c) {
    const std::vector<double>& t = times_[c];
    info.clips.push_back({set_.clips[c]->name, info.times.size(), t.size(), fps[c], t.empty() ? 0 : t.back() - t.front(), false});
    info.times.insert(info.times.end(), t.begin(), t.end());
  }
  if (planned) info.plan = {to_string(planned->format.type), planned->step, planned->error(), planned->encoding_error,
                            planned->interpolation_error, planned->bytes};
  // A slice that is not the head skips it where the encoding stores positions exactly (dqskin's float) and
  // no --max-error is relative to the clip's size: the bounds then only go into vat.json, which the head
  // writes, and the "one pose" rule needs no encoding bound (half's depends on the stored magnitudes).
  // Every frame deformed once more costs a slice as much as about a tenth of its own work.
  const bool measured = !set_.sliced() || set_.head || format.profile != VatProfile::kDqskin ||
                        format.type != TexelType::kFloat32 || (o.max_error > 0 && o.max_error_relative);
  VatMeasure measure(e, info.clips);
  for (size_t c = 0; c < set_.clips.size() && measured; ++c) {
    const size_t first = info.clips[c].first_frame;
    deformer.run(set_.clips[c]->clip, times_[c], [&](const DeformedBatch& batch) {
      for (size_t k = 0; k < batch.frame_count; ++k) {
        const size_t f = first + batch.first_frame + k;
        if (f == 0 && format.profile == VatProfile::kHoudini) rest = copy_frame(batch, k);
        measure.add(distinct_vertices(frame_view(batch, k), sharing_), f, info.times.size());
      }
    });
  }
  if (measured) measure.finish(info, what);

  const std::string folder = options.plan.out_dir + "/" + set_.folder;
  const VatFileNames names = vat_file_names(format, safe_name(input.stem));
  std::string rest_glb = encode_rest_glb(*input.asset, input.instances, frame_view(rest, 0), e.layout, input.stem, look);
  const VatSlice slice{set_.first, set_.end, set_.head};
  writer_ = std::make_unique<VatWriter>(std::move(e), std::move(info), folder, names, std::move(rest_glb), o.check, slice);
  // Several clips: each has its own figures, its motion measured from its own first frame.
  if (set_.clips.size() > 1 && writer_->frame_check()) {
    std::vector<size_t> starts;
    for (size_t c = 0, first = 0; c < times_.size(); first += times_[c].size(), ++c) starts.push_back(first);
    writer_->frame_check()->set_clip_starts(std::move(starts));
  }
}

size_t VatClipBake::frames() const {
  size_t n = 0;
  for (const std::vector<double>& t : times_) n += t.size();
  return n;
}

bool VatClipBake::uses_bake_frames() const { return set_.clips.size() == 1 && times_[0] == set_.clips[0]->times; }

void VatClipBake::encode_own_frames(Deformer& deformer) {
  for (size_t c = 0; c < set_.clips.size(); ++c)
    deformer.run(set_.clips[c]->clip, times_[c], [&](const DeformedBatch& batch) {
      for (size_t k = 0; k < batch.frame_count; ++k) writer_->append(distinct_vertices(frame_view(batch, k), sharing_));
    });
}

VatClipBake::~VatClipBake() = default;

void VatClipBake::append(const FrameView& frame, size_t f) {
  const VatSlice& slice = writer_->slice();
  if (f >= slice.first && f < slice.end) writer_->append(distinct_vertices(frame, sharing_));
  else if (f == 0) writer_->append_first(distinct_vertices(frame, sharing_));
  else if (f == slice.end) writer_->append_next(distinct_vertices(frame, sharing_));
}

void VatClipBake::complete_images() {
  if (complete_) return;
  writer_->finish();
  complete_ = true;
}

std::vector<std::pair<std::string, Committed>> VatClipBake::finish(Deformer& deformer, const CommitOptions& commit) {
  complete_images();
  const TextureOptions& o = options_.textures;
  std::optional<DecodeCheck> whole;  // over every clip: the side file's figures
  if (o.check) {
    // The frames were checked in memory as they were encoded (VatWriter's VatFrameCheck); the files are
    // read back for the midpoints a runtime interpolates, the only poses deformed again, and their
    // digests (docs/DESIGN.md §4.8). One reader for the whole texture; midpoints within each clip only.
    VatDecodeChecker checker(*writer_);
    size_t first = 0;
    // A slice checks the midpoints after each of its frames (the last one's with the next slice's first).
    const VatSlice& slice = writer_->slice();
    for (size_t c = 0; c < set_.clips.size(); ++c) {
      const std::vector<double>& t = times_[c];
      std::vector<double> midpoints;
      const size_t from = std::max(first, slice.first) - first;
      for (size_t f = from; f + 1 < t.size() && first + f < slice.end; ++f) midpoints.push_back(t[f] + (t[f + 1] - t[f]) / 2);
      if (!midpoints.empty())
        deformer.run(set_.clips[c]->clip, midpoints, [&](const DeformedBatch& batch) {
          for (size_t k = 0; k < batch.frame_count; ++k)
            checker.midpoint(first + from + batch.first_frame + k, distinct_vertices(frame_view(batch, k), sharing_));
        });
      first += t.size();
    }
    whole = checker.finish();
    if (set_.sliced()) {
      nlohmann::json share = checker.share().to_json();
      share["slice"] = {set_.first, set_.end};  // the merge checks that the slices cover the clip once
      share_ = share.dump();
    }
    for (size_t c = 0; c < set_.clips.size(); ++c) {
      const std::string what = "clip " + set_.clips[c]->name;
      const DecodeCheck check = checker.clip_result(c);
      checks_.push_back(check);
      // A clip that moves further than its encoding resolves (float noise aside) must not decode to one pose.
      const double resolvable =
          std::max(2 * position_encoding_bound(writer_->encoding()), 1e-6 * writer_->clip_bounds().diagonal());
      if (checker.reference_motion(c) > resolvable && checker.decoded_motion(c) == 0)
        throw InputError(what + ": every frame of the texture decodes to one pose while the clip moves " +
                         length_text(checker.reference_motion(c)) + " (a bake of the rest pose?)");
      if (o.max_error > 0) {
        const double limit = o.max_error_relative ? o.max_error * writer_->clip_bounds().diagonal() : o.max_error;
        const double worst = std::max(check.max_error, check.max_midpoint_error);
        if (worst > limit)
          throw InputError(what + ": the texture decodes with errors up to " + length_text(check.max_error) +
                           " at frames and " + length_text(check.max_midpoint_error) + " between them, over --max-error " +
                           length_text(limit));
      }
    }
  }
  // One clip: the texture's figures are the clip's; several: each clip's too, in the clip table.
  const std::vector<DecodeCheck> per_clip = set_.clips.size() > 1 ? checks_ : std::vector<DecodeCheck>();
  std::vector<std::pair<std::string, Committed>> files = writer_->commit(whole ? &*whole : nullptr, commit, per_clip);
  for (auto& [name, committed] : files) name = set_.folder + "/" + name;
  return files;
}

}  // namespace dqskin::bake_detail
