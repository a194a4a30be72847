// The rotation-key checks of `dqskin lint`. glTF 2.0 §3.11 asks for unit quaternions as rotation keys;
// and a runtime that interpolates LINEAR or CUBICSPLINE keys component-wise, without the shortest-path sign
// check of Appendix C's slerp, turns the long way round between neighbours q_k, q_k+1 with
// dot(q_k, q_k+1) < 0. And §3.11 allows one channel per node and path in an animation.
#include "lint_checks.hpp"

#include "dqskin/job.hpp"

#include <algorithm>
#include <cmath>

namespace dqskin::lint {
namespace {

struct Q {
  double x, y, z, w;
};

double dot(const Q& a, const Q& b) { return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w; }

}  // namespace

void check_rotation_keys(const gltf::SkinData& data, const LintOptions& options, Findings& out) {
  const Asset& asset = data.structure;
  for (const gltf::RotationSource& source : data.rotations) {
    check_cancelled(options.cancel);
    const Clip& clip = asset.clips[source.clip];
    const Channel& ch = clip.channels[source.channel];
    const bool cubic = ch.interpolation == Interpolation::kCubicSpline;
    const size_t stride = cubic ? 12 : 4, offset = cubic ? 4 : 0;  // CUBICSPLINE: in-tangent, value, out-tangent
    const std::string& name = asset.nodes[size_t(ch.node)].name;
    const std::string where = "animation '" + clip.name + "' channel " + std::to_string(source.channel) + " (node " +
                              std::to_string(ch.node) + (name.empty() ? "" : " '" + name + "'") + ")";
    // Normalized integer keys (§3.11) round each component by up to half a unit: a length error up to
    // 1/largest value is their rounding, not the file's.
    const double unit = normalized_max(source.output_component);
    const double tolerance = std::max(options.unit_tolerance, unit > 0 ? 1 / unit : 0.0);
    Q previous{};
    double previous_length = 0;
    for (size_t k = 0; k < ch.times.size(); ++k) {
      const float* v = &ch.values[k * stride + offset];
      const Q q{double(v[0]), double(v[1]), double(v[2]), double(v[3])};
      const double length = std::sqrt(dot(q, q));
      LintExample e;
      e.where = where;
      e.key = static_cast<long long>(k);
      if (std::abs(length - 1) > tolerance) {
        e.value = length;
        out["rotation-not-unit"].add(std::abs(length - 1), e, [&] {
          return "rotation key " + std::to_string(k) + " has length " + number(length) + " in " + where +
                 (length > 0 ? "" : " (no rotation; --fix takes the nearest valid key of the channel)");
        });
      }
      // STEP keys are never interpolated, so their signs do not matter.
      if (k > 0 && ch.interpolation != Interpolation::kStep && length > 0 && previous_length > 0) {
        const double d = dot(previous, q) / (length * previous_length);
        if (d < 0) {
          e.value = d;
          out["hemisphere-flip"].add(-d, e, [&] {
            return "rotation keys " + std::to_string(k - 1) + " and " + std::to_string(k) +
                   " lie in opposite hemispheres (dot " + number(d) + ") in " + where;
          });
        }
      }
      previous = q;
      previous_length = length;
    }
  }
}

void check_channels(const gltf::SkinData& data, const LintOptions& options, Findings& out) {
  for (const gltf::DuplicateChannel& d : data.duplicate_channels) {
    check_cancelled(options.cancel);
    LintExample e;
    e.where = "animation '" + data.structure.clips[d.animation].name + "' channel " + std::to_string(d.second);
    e.value = double(d.first);  // the channel it repeats
    out[d.identical ? "repeated-channel" : "duplicate-channel"].add(0, e, [&] {
      return d.message + "; --fix keeps channel " + std::to_string(d.first);
    });
  }
}

}  // namespace dqskin::lint
