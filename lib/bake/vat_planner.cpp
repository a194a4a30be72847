#include "vat_planner.hpp"

#include "vat_bake.hpp"
#include "../base/length_text.hpp"
#include "../texture/vat_measure.hpp"
#include "../texture/vat_side_files.hpp"

#include "../base/byte_size.hpp"
#include "dqskin/error.hpp"
#include "../texture/texture_output.hpp"
#include "../write/vertex_sharing.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace dqskin::bake_detail {


using namespace texture;

namespace {


// The frame decimations weighed: every k-th frame of the grid.
constexpr size_t kSteps[] = {1, 2, 3, 4, 6, 8};

// Kept frames of a decimation by k over F frames: 0, k, …, m·k with m·k the first multiple of k at or
// after the last frame (past it, the clip holds its last pose), so the texture covers the whole clip.
size_t kept_frames(size_t frames, size_t k) { return (frames - 1 + k - 1) / k + 1; }

// The interpolation errors of every decimation, measured on samples at every frame and midpoint of the
// clip's grid (half-frame steps), streamed in order: when a kept sample arrives, the samples since the
// previous kept one are compared with the straight line between the two.
class InterpolationErrors {
public:
  InterpolationErrors(std::vector<size_t> steps, size_t samples)
      : steps_(std::move(steps)), samples_(samples), errors_(steps_.size(), 0.0),
        ring_(2 * *std::max_element(steps_.begin(), steps_.end()) + 1) {}

  // Regular sample j (time of frame j / 2, midpoints at odd j).
  void add(size_t j, std::vector<float> positions) {
    ring_[j % ring_.size()] = std::move(positions);
    for (size_t s = 0; s < steps_.size(); ++s) {
      const size_t span = 2 * steps_[s];
      if (j > 0 && j % span == 0) compare(s, j - span, ring_[j % ring_.size()], j);
    }
  }

  // The pose past the end that decimation s keeps (at half-frame index `at` > the last sample).
  void add_past_end(size_t s, size_t at, const std::vector<float>& positions) {
    const size_t span = 2 * steps_[s];
    const size_t a = at - span;
    compare(s, a, positions, std::min(at, samples_));
  }

  double error(size_t s) const { return errors_[s]; }

private:
  // Samples (a, end) against the line from sample a to `b` (at index a + span).
  void compare(size_t s, size_t a, const std::vector<float>& b, size_t end) {
    const size_t span = 2 * steps_[s];
    const std::vector<float>& pa = ring_[a % ring_.size()];
    for (size_t j = a + 1; j < end && j < samples_; ++j) {
      const std::vector<float>& p = ring_[j % ring_.size()];
      const float w = float(j - a) / float(span);
      double worst = 0;
      for (size_t i = 0; i + 2 < p.size(); i += 3) {
        const glm::vec3 x(pa[i], pa[i + 1], pa[i + 2]), y(b[i], b[i + 1], b[i + 2]), q(p[i], p[i + 1], p[i + 2]);
        worst = std::max(worst, double(glm::length(x + (y - x) * w - q)));
      }
      errors_[s] = std::max(errors_[s], worst);
    }
  }

  std::vector<size_t> steps_;
  size_t samples_;
  std::vector<double> errors_;
  std::vector<std::vector<float>> ring_;
};

uint64_t image_bytes(const VatLayout& l) {
  VatEncoding e;
  e.layout = l;
  uint64_t per_texel = uint64_t(l.position_channels()) * channel_bytes(l.format.type);
  if (const std::optional<TexelType> type = e.normal_image_type()) per_texel += uint64_t(normal_channels(e)) * channel_bytes(*type);
  uint64_t bytes = 0;
  for (size_t p = 0; p < l.pages; ++p) bytes += uint64_t(l.width) * l.page_height(p) * per_texel;
  return bytes;
}

std::string fps_text(double fps) {
  char text[32];
  std::snprintf(text, sizeof text, "%g fps", fps);
  return text;
}

std::string choice_text(const VatChoice& c) {
  std::string s = to_string(c.format.type);
  if (c.fps > 0) s += " at " + fps_text(c.fps);
  return s;
}

}  // namespace

bool planner_active(const TextureOptions& o) { return o.max_error > 0 || o.max_bytes > 0; }

VatPlan plan_vat(Deformer& deformer, const InputPlan& input, const TextureClips& set, const TextureOptions& o,
                 const std::vector<float>& rest) {
  const VatFormat base = vat_format(o);
  const std::string& what = set.what;
  const SharedVertexLayout sharing = shared_vertex_layout(*input.asset, input.instances);
  std::vector<TexelType> types;
  if (!o.encoding.empty()) {
    types.push_back(base.type);
  } else {
    for (TexelType t : {TexelType::kFloat32, TexelType::kHalf, TexelType::kUnorm16, TexelType::kUnorm8}) {
      VatFormat f = base;
      f.type = t;
      // Houdini's LDR remap takes the clip's absolute bounds for offsets and clips them: not offered.
      if (unsupported_reason(f).empty() && !(base.profile == VatProfile::kHoudini && is_png(t))) types.push_back(t);
    }
  }
  // A decimation applies to every clip of the texture: offered when each clip's times are a grid longer
  // than the step.
  struct ClipGrid {
    size_t frames = 0;
    bool grid = false;
    double spacing = 0;
  };
  std::vector<ClipGrid> grids;
  for (const ClipPlan* clip : set.clips) {
    const std::vector<double>& t = clip->times;
    ClipGrid g;
    g.frames = t.size();
    g.grid = clip->fps > 0 && g.frames >= 2;
    g.spacing = g.grid ? (t.back() - t.front()) / double(g.frames - 1) : 0.0;
    grids.push_back(g);
  }
  std::vector<size_t> steps;
  for (size_t k : kSteps)
    if (k == 1 || std::all_of(grids.begin(), grids.end(), [&](const ClipGrid& g) { return g.grid && k < g.frames; }))
      steps.push_back(k);

  VatEncoding e;
  e.rest = rest;
  e.layout.format = base;
  Box stored, clip_box;
  std::vector<double> interpolation_errors(steps.size(), 0.0);
  for (size_t c = 0; c < set.clips.size(); ++c) {
    const std::vector<double>& t = set.clips[c]->times;
    const ClipGrid& g = grids[c];
    // Samples: every frame and midpoint, then the poses past the end that decimations keep.
    std::vector<double> times = frames_and_midpoints(t);
    const size_t regular = times.size();
    std::map<size_t, std::vector<size_t>> past_end;  // last kept frame past the end → the steps keeping it
    for (size_t s = 0; s < steps.size(); ++s) {
      const size_t last = (kept_frames(g.frames, steps[s]) - 1) * steps[s];
      if (last > g.frames - 1) past_end[last].push_back(s);
    }
    for (const auto& [frame, unused] : past_end) times.push_back(t.back() + double(frame - (g.frames - 1)) * g.spacing);

    InterpolationErrors interpolation(steps, regular);
    auto past_end_at = past_end.begin();
    deformer.run(set.clips[c]->clip, times, [&](const DeformedBatch& batch) {
      for (size_t k = 0; k < batch.frame_count; ++k) {
        const size_t j = batch.first_frame + k;
        std::vector<float> positions = all_positions(distinct_vertices(frame_view(batch, k), sharing));
        if (j >= regular) {  // a pose past the end
          for (size_t s : past_end_at->second) interpolation.add_past_end(s, 2 * past_end_at->first, positions);
          ++past_end_at;
          continue;
        }
        if (j % 2 == 0) {
          if (c == 0 && j == 0 && base.profile == VatProfile::kHoudini) e.rest = positions;
          for (size_t v = 0; 3 * v < positions.size(); ++v) {
            const glm::vec3 p(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
            clip_box.add(glm::dvec3(p));
            stored.add(stored_position(e, v, p));
          }
        }
        interpolation.add(j, std::move(positions));
      }
    });
    for (size_t s = 0; s < steps.size(); ++s) interpolation_errors[s] = std::max(interpolation_errors[s], interpolation.error(s));
  }
  // The texture's rate for messages: the clips' common one (none when they differ).
  const bool one_rate = std::all_of(grids.begin(), grids.end(), [&](const ClipGrid& g) {
    return g.grid && grids.front().grid && g.spacing == grids.front().spacing;
  });

  size_t vertices = 0;
  for (const VatSource& s : vat_sources(*input.asset, input.instances)) vertices += s.vertices;
  VatPlan plan;
  plan.diagonal = clip_box.diagonal();
  for (TexelType type : types)
    for (size_t s = 0; s < steps.size(); ++s) {
      VatChoice c;
      c.format = base;
      c.format.type = type;
      c.step = steps[s];
      c.fps = one_rate ? 1.0 / (grids.front().spacing * double(c.step)) : 0.0;
      c.frames = 0;
      for (const ClipGrid& g : grids) c.frames += kept_frames(g.frames, c.step);
      c.interpolation_error = interpolation_errors[s];
      try {
        e.layout = plan_vat_layout(c.format, vertices, c.frames, o.max_size, o.pot, what);
        c.width = e.layout.width;
        c.height = e.layout.height;
        c.pages = e.layout.pages;
        c.bytes = image_bytes(e.layout);
        e.stored = stored;
        e.remapped = base.profile == VatProfile::kOpenVat || is_png(type);
        e.bounds = !e.remapped ? Box()
                   : base.profile == VatProfile::kHoudini ? houdini_encoded_bounds(clip_box, e.layout, what)
                                                          : decimal_bounds(stored);
        c.encoding_error = position_encoding_bound(e);
      } catch (const InputError& error) {
        c.unfit = error.what();
      }
      plan.choices.push_back(std::move(c));
    }

  const double max_error = o.max_error_relative ? o.max_error * plan.diagonal : o.max_error;
  if (o.max_error > 0) plan.budget = "--max-error " + length_text(max_error);
  if (o.max_bytes > 0) plan.budget += (plan.budget.empty() ? "" : ", ") + std::string("--max-bytes ") + byte_size(o.max_bytes);
  auto within_bytes = [&](const VatChoice& c) { return c.unfit.empty() && (o.max_bytes == 0 || c.bytes <= o.max_bytes); };
  auto within_error = [&](const VatChoice& c) { return c.unfit.empty() && (o.max_error == 0 || c.error() <= max_error); };
  // With an error budget the fewest bytes that meet it; without, the smallest error the bytes allow.
  auto better = [&](const VatChoice& a, const VatChoice& b) {
    if (o.max_error > 0) return a.bytes != b.bytes ? a.bytes < b.bytes : a.error() < b.error();
    return a.error() != b.error() ? a.error() < b.error() : a.bytes < b.bytes;
  };
  std::optional<size_t> chosen;
  for (size_t i = 0; i < plan.choices.size(); ++i) {
    const VatChoice& c = plan.choices[i];
    if (within_bytes(c) && within_error(c) && (!chosen || better(c, plan.choices[*chosen]))) chosen = i;
  }
  if (!chosen) {
    std::optional<size_t> best_in_bytes, fewest_in_error;
    for (size_t i = 0; i < plan.choices.size(); ++i) {
      const VatChoice& c = plan.choices[i];
      if (within_bytes(c) && (!best_in_bytes || c.error() < plan.choices[*best_in_bytes].error())) best_in_bytes = i;
      if (within_error(c) && (!fewest_in_error || c.bytes < plan.choices[*fewest_in_error].bytes)) fewest_in_error = i;
    }
    std::string message = what + ": no texture meets " + plan.budget;
    if (best_in_bytes) {
      const VatChoice& c = plan.choices[*best_in_bytes];
      message += std::string("; the most accurate") + (o.max_bytes > 0 ? " within --max-bytes" : "") + " is " +
                 choice_text(c) + " (" + length_text(c.error()) + ", " + byte_size(c.bytes) + ")";
    }
    if (fewest_in_error) {
      const VatChoice& c = plan.choices[*fewest_in_error];
      message += "; within --max-error the smallest is " + choice_text(c) + " (" + byte_size(c.bytes) + ")";
    }
    if (!best_in_bytes && !fewest_in_error) message += "; " + plan.choices.front().unfit;
    throw InputError(message);
  }
  plan.chosen = *chosen;
  const VatChoice& c = plan.choices[plan.chosen];
  for (size_t clip = 0; clip < set.clips.size(); ++clip) {
    const std::vector<double>& t = set.clips[clip]->times;
    const ClipGrid& g = grids[clip];
    std::vector<double> kept;
    for (size_t i = 0; i < kept_frames(g.frames, c.step); ++i) {
      const size_t f = i * c.step;
      kept.push_back(f < g.frames ? t[f] : t.back() + double(f - (g.frames - 1)) * g.spacing);
    }
    plan.times.push_back(std::move(kept));
    plan.fps.push_back(g.grid ? 1.0 / (g.spacing * double(c.step)) : 0.0);
  }
  return plan;
}

std::vector<std::string> dry_run_plans(const InputPlan& input, const BakeOptions& options) {
  DeformerOptions d;
  d.mode = options.mode;
  d.backend = has_gpu_path(options.mode) ? Backend::kFastCpu : Backend::kCpu;
  d.threads = options.jobs;
  std::unique_ptr<Deformer> deformer = make_deformer(nullptr, *input.asset, input.instances, d);
  std::vector<float> rest;
  if (vat_format(options.textures).profile == VatProfile::kOpenVat) {
    const double zero = 0;
    const SharedVertexLayout sharing = shared_vertex_layout(*input.asset, input.instances);
    deformer->run(nullptr, std::span(&zero, 1),
                  [&](const DeformedBatch& batch) { rest = all_positions(distinct_vertices(frame_view(batch, 0), sharing)); });
  }
  std::vector<std::string> lines;
  for (const TextureClips& set : texture_clip_sets(input, options.textures.combine_clips)) {
    if (!set.mine) continue;
    std::vector<std::string> table = describe(plan_vat(*deformer, input, set, options.textures, rest), set.what);
    lines.push_back(input.path + ":");
    lines.insert(lines.end(), table.begin(), table.end());
  }
  return lines;
}

std::vector<std::string> describe(const VatPlan& plan, const std::string& what) {
  std::vector<std::string> lines;
  lines.push_back("plan for " + what + (plan.budget.empty() ? "" : " (" + plan.budget + ")") +
                  ": type, frames, image, GPU bytes, expected error = encoding + interpolation");
  for (size_t i = 0; i < plan.choices.size(); ++i) {
    const VatChoice& c = plan.choices[i];
    char text[320];
    if (!c.unfit.empty()) {
      std::snprintf(text, sizeof text, "    %-6s %5zu frames%s: does not fit (%s)", to_string(c.format.type), c.frames,
                    c.fps > 0 ? (" at " + fps_text(c.fps)).c_str() : "", c.unfit.c_str());
    } else {
      const std::string pages = c.pages > 1 ? " x " + std::to_string(c.pages) + " pages" : "";
      std::snprintf(text, sizeof text, "  %s %-6s %5zu frames%s, %zu x %zu%s, %s, %s = %s + %s%s",
                    i == plan.chosen ? "*" : " ", to_string(c.format.type), c.frames,
                    c.fps > 0 ? (" at " + fps_text(c.fps)).c_str() : "", c.width, c.height, pages.c_str(),
                    byte_size(c.bytes).c_str(), length_text(c.error()).c_str(), length_text(c.encoding_error).c_str(),
                    length_text(c.interpolation_error).c_str(), i == plan.chosen ? "  <- chosen" : "");
    }
    lines.push_back(text);
  }
  return lines;
}

}  // namespace dqskin::bake_detail
