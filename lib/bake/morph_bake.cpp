#include "morph_bake.hpp"

#include "../anim/keyframe_reduction.hpp"
#include "../base/parallel_for.hpp"
#include "../base/length_text.hpp"
#include "../write/morph_glb.hpp"
#include "../base/saturating.hpp"
#include "dqskin/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <stdexcept>

#include <glm/gtc/type_ptr.hpp>

namespace dqskin::bake_detail {


namespace {

// Morph targets that a WebGL2 viewer can be counted on to draw. three.js (src/renderers/webgl/
// WebGLMorphtargets.js, r187) packs every target of a geometry into one DataArrayTexture whose depth is the
// target count, and WebGL2 guarantees only MAX_ARRAY_TEXTURE_LAYERS ≥ 256; its vertex shader
// (src/renderers/shaders/ShaderChunk/morphtarget_pars_vertex.glsl.js) declares `uniform float
// morphTargetInfluences[MORPHTARGETS_COUNT]`, which takes one of WebGL2's guaranteed 256
// MAX_VERTEX_UNIFORM_VECTORS per target (GLSL ES 3.00 packs each array element into a vector of its own),
// shared with the material's own uniforms; model-viewer draws with three.js. Babylon.js
// (Morph/morphTargetManager.js, 9.x) keeps targets in a texture array too, and past the device's
// texture2DArrayMaxLayerCount falls back to vertex attributes with at most
// MaxActiveMorphTargetsInVertexAttributeMode = 8 active targets, which one-hot weights (two active between
// keys) stay within. 200 leaves 56 of the 256 vectors to the material.
constexpr size_t kPortableMorphTargets = 200;

// Texels a WebGL2 viewer can be counted on to hold per primitive: three.js lays a primitive's targets out
// as rows of MAX_TEXTURE_SIZE texels, one per vertex and attribute morphed (position, then normal), and a
// layer must fit MAX_TEXTURE_SIZE rows too (WebGLMorphtargets.js, r187); WebGL2 guarantees 2048.
constexpr size_t kPortableMorphTexels = size_t(2048) * 2048;

// The largest of several threads' values.
struct Max {
  std::mutex mutex;
  double value = 0;
  void add(double v) {
    const std::lock_guard<std::mutex> lock(mutex);
    value = std::max(value, v);
  }
};

}  // namespace

std::vector<std::string> morph_viewer_warnings(const std::string& what, size_t targets,
                                               const std::vector<std::pair<size_t, bool>>& primitives) {
  std::vector<std::string> warnings;
  if (targets > kPortableMorphTargets) {
    std::string w = what;
    w += ": ";
    w += std::to_string(targets);
    w += " morph targets; three.js (and model-viewer) on WebGL2 is only sure to draw about ";
    w += std::to_string(kPortableMorphTargets);
    w += " (256 array-texture layers and vertex uniform vectors guaranteed); --max-error keeps fewer keyframes";
    warnings.push_back(std::move(w));
  }
  for (size_t p = 0; p < primitives.size(); ++p) {
    const auto [vertices, normals] = primitives[p];
    const size_t per_vertex = normals ? 2 : 1;
    if (vertices * per_vertex <= kPortableMorphTexels) continue;
    std::string w = what;
    w += ": primitive ";
    w += std::to_string(p);
    w += " has ";
    w += std::to_string(vertices);
    w += " vertices; three.js on WebGL2 is only sure to hold ";
    w += std::to_string(kPortableMorphTexels / per_vertex);
    w += " in a morph-target texture (2048 x 2048 texels guaranteed)";
    warnings.push_back(std::move(w));
  }
  return warnings;
}

std::string morph_file(const ClipPlan& clip) { return clip.folder + "/animation.glb"; }

uint64_t morph_frames_bytes(const InputPlan& input, const ClipPlan& clip) {
  const uint64_t vertices = shared_vertex_layout(*input.asset, input.instances).vertices;
  return saturating::mul(saturating::mul(vertices, clip.times.size()), 24);
}

uint64_t planned_morph_bytes(const InputPlan& input, const ClipPlan& clip) {
  const Asset& asset = *input.asset;
  uint64_t vertices = shared_vertex_layout(asset, input.instances).vertices, indices = 0, images = 0;
  for (const MeshInstance& inst : input.instances)
    for (const Primitive& p : asset.meshes[size_t(inst.mesh)].primitives) indices += p.indices.size();
  for (const EncodedImage& image : asset.images) images += image.bytes.size();
  const uint64_t frames = clip.times.size();
  // Per vertex: the mesh and up to four texture coordinate or colour sets; per vertex and frame a float
  // position and normal; per frame a target's JSON and its weights.
  using saturating::add, saturating::mul;
  return add(add(add(16384, images), add(mul(indices, 4), mul(vertices, 88))),
             add(mul(mul(vertices, frames), 24), add(mul(frames, 256), mul(mul(frames, frames), 4))));
}

MorphClipBake::MorphClipBake(const InputPlan& input, const ClipPlan& clip, const BakeOptions& options)
    : input_(input), clip_(clip), options_(options), what_("clip " + clip.name),
      sharing_(shared_vertex_layout(*input.asset, input.instances)) {
  const Asset& asset = *input.asset;
  size_t flat = 0;
  for (const MeshInstance& inst : input.instances)
    for (const Primitive& p : asset.meshes[size_t(inst.mesh)].primitives) {
      if (!sharing_.writes(flat++)) continue;  // its vertices are an earlier primitive's (vertex_sharing.hpp)
      first_.push_back(vertices_);
      with_normals_.push_back(!p.normals_generated && !p.normals.empty());
      vertices_ += p.vertex_count();
    }
  if (vertices_ == 0) throw InputError(what_ + ": no vertices to bake into morph targets");
  // §3.11: an animation's input times must increase strictly, as the floats written.
  for (size_t f = 1; f < clip.times.size(); ++f)
    if (!(float(clip.times[f]) > float(clip.times[f - 1])))
      throw InputError(what_ + ": a morph-target animation needs increasing frame times; frame " + std::to_string(f) +
                       " is not after the one before it");
  positions_.reserve(clip.times.size());
  normals_.reserve(clip.times.size());
}

void MorphClipBake::append(const FrameView& all) {
  const FrameView frame = distinct_vertices(all, sharing_);
  std::vector<float> positions(3 * vertices_), normals(3 * vertices_, 0.0f);
  for (size_t p = 0; p < frame.primitives.size() && p < first_.size(); ++p) {
    const PrimitiveView& view = frame.primitives[p];
    std::copy(view.positions.begin(), view.positions.begin() + std::ptrdiff_t(3 * view.vertices), &positions[3 * first_[p]]);
    if (!with_normals_[p] || view.normals.empty()) continue;
    for (size_t v = 0; v < view.vertices; ++v) {
      // The validator requires unit normals in the mesh (§3.7.2.1); every key is treated alike.
      const glm::vec3 n = glb::unit_or(glm::dvec3(view.normals[3 * v], view.normals[3 * v + 1], view.normals[3 * v + 2]), {0, 0, 1});
      std::copy(&n.x, &n.x + 3, &normals[3 * (first_[p] + v)]);
    }
  }
  positions_.push_back(std::move(positions));
  normals_.push_back(std::move(normals));
}

MorphClipResult MorphClipBake::finish(const glb::Appearance& appearance, unsigned threads) {
  const size_t frames = positions_.size();
  if (frames != clip_.times.size())
    throw std::logic_error("MorphClipBake: " + std::to_string(frames) + " frames appended, the clip has " +
                           std::to_string(clip_.times.size()));
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
  for (const std::vector<float>& frame : positions_)
    for (size_t i = 0; i < frame.size(); i += 3) {
      const glm::dvec3 p(frame[i], frame[i + 1], frame[i + 2]);
      lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
  const TextureOptions& t = options_.textures;
  const double limit = t.max_error > 0 ? (t.max_error_relative ? t.max_error * glm::distance(lo, hi) : t.max_error) : 0;

  glb::MorphAnimation a;
  a.name = input_.stem;
  a.clip = clip_.name;
  if (options_.morph.quantize) a.grid = glb::MorphGrid::over(lo, hi);
  if (limit > 0 && a.grid.bound() > limit)
    throw InputError(what_ + ": --morph-quantize's grid (a step of " + length_text(a.grid.step) + ") stores positions within " +
                     length_text(a.grid.bound()) + ", over --max-error " + length_text(limit));
  const std::vector<float>& base = positions_[0];
  auto stored = [&](size_t f, size_t v) { return glb::stored_position(a.grid, &base[3 * v], &positions_[f][3 * v]); };
  // Frame i between keys ka and kb as a viewer shows it: the keys' stored positions interpolated linearly.
  auto fraction = [&](size_t i, size_t ka, size_t kb) {
    return ka == kb ? 0.0 : (clip_.times[i] - clip_.times[ka]) / (clip_.times[kb] - clip_.times[ka]);
  };
  auto error = [&](size_t i, size_t ka, size_t kb) {
    const double s = fraction(i, ka, kb);
    double worst = 0;
    for (size_t v = 0; v < vertices_; ++v) {
      const glm::dvec3 shown = (1 - s) * stored(ka, v) + s * stored(kb, v);
      worst = std::max(worst, glm::distance(shown, glm::dvec3(glm::make_vec3(&positions_[i][3 * v]))));
    }
    return worst;
  };
  std::vector<size_t> keys;
  if (limit > 0) {
    keys = reduce_keyframes(frames, limit, error, threads);
  } else {
    for (size_t f = 0; f < frames; ++f) keys.push_back(f);
  }

  // Target normals as normalized SHORTs, per key and primitive, as the encoder decides.
  std::vector<std::vector<char>> short_normals(frames, std::vector<char>(first_.size(), 0));
  for (size_t k : keys)
    for (size_t p = 0; p < first_.size(); ++p) {
      const size_t n = (p + 1 < first_.size() ? first_[p + 1] : vertices_) - first_[p];
      short_normals[k][p] = glb::short_normal_target(a.grid, std::span(normals_[0]).subspan(3 * first_[p], 3 * n),
                                                     std::span(normals_[k]).subspan(3 * first_[p], 3 * n));
    }
  // The measurement: every baked frame, between the keys around it.
  Max position_error, normal_error;
  concurrency::parallel_for(frames, threads, [&](size_t i) {
    const auto next = std::lower_bound(keys.begin(), keys.end(), i);  // the last frame is a key
    const size_t kb = *next, ka = kb == i ? i : *(next - 1);
    position_error.add(error(i, ka, kb));
    const double s = fraction(i, ka, kb);
    double worst = 0;
    for (size_t p = 0; p < first_.size(); ++p) {
      if (!with_normals_[p]) continue;
      const size_t end = p + 1 < first_.size() ? first_[p + 1] : vertices_;
      for (size_t v = first_[p]; v < end; ++v) {
        auto normal = [&](size_t k) { return glb::stored_normal(a.grid, short_normals[k][p], &normals_[0][3 * v], &normals_[k][3 * v]); };
        const glm::dvec3 shown = (1 - s) * normal(ka) + s * normal(kb);
        const glm::dvec3 truth(glm::make_vec3(&normals_[i][3 * v]));
        // atan2 of |cross| and dot: exact for small angles, where acos of a dot near 1 is not.
        worst = std::max(worst, std::atan2(glm::length(glm::cross(shown, truth)), glm::dot(shown, truth)));
      }
    }
    normal_error.add(glm::degrees(worst));
  });
  if (limit > 0 && position_error.value > limit)
    throw InputError(what_ + ": the morph targets decode with errors up to " + length_text(position_error.value) +
                     ", over --max-error " + length_text(limit));

  // The frames between keys are freed: the measurement above was their last reader, and the encoding holds
  // its file's bytes beside the keys.
  for (size_t f = 0, next = 0; f < frames; ++f) {
    if (next < keys.size() && keys[next] == f) {
      ++next;
    } else {
      positions_[f] = {};
      normals_[f] = {};
    }
  }
  for (size_t k : keys) {
    a.times.push_back(clip_.times[k]);
    a.positions.push_back(positions_[k]);
    a.normals.push_back(normals_[k]);
    if (k == keys.front()) continue;
    char name[48];
    std::snprintf(name, sizeof name, "frame_%0*d", clip_.number_width, clip_.numbers[k]);
    a.target_names.push_back(name);
  }
  a.with_normals = with_normals_;
  glb::MorphGlbStats stats;
  MorphClipResult out;
  out.spill = std::make_unique<AtomicFile>(options_.plan.out_dir + "/" + morph_file(clip_), false);
  AtomicFile& spill = *out.spill;
  try {
    out.glb = glb::encode_morph_glb(*input_.asset, input_.instances, appearance, a, &stats,
                                    [&spill](std::span<const char> bytes) { spill.write(bytes); });
  } catch (const OutputError& e) {  // past 4 GiB: fewer frames (--fps, --max-error) would fit
    throw OutputError(what_ + ": " + e.what());
  }
  spill.hand_over();  // closes the temporary: the bake reads it back into the file
  out.check = {input_.path, clip_.name, frames, keys.size(), position_error.value, normal_error.value,
               out.glb.size(), stats.sparse_accessors, a.grid.on()};
  std::vector<std::pair<size_t, bool>> primitives;
  for (size_t p = 0; p < first_.size(); ++p)
    primitives.emplace_back((p + 1 < first_.size() ? first_[p + 1] : vertices_) - first_[p], bool(with_normals_[p]));
  out.warnings = morph_viewer_warnings(what_, stats.targets, primitives);
  return out;
}

}  // namespace dqskin::bake_detail
