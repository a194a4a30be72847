// `dqskin diff BAKE_A BAKE_B`: two folders that `dqskin bake` wrote, frame files paired by relative path and
// compared vertex by vertex (bake keeps each input's vertex order), textures texel by texel.
#include "baked_file.hpp"
#include "diff_numbers.hpp"
#include "../base/saturating.hpp"

#include "../base/byte_size.hpp"
#include "dqskin/error.hpp"
#include "dqskin/geometry_diff.hpp"
#include "dqskin/job.hpp"
#include "dqskin/memory_ceiling.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <filesystem>
#include <map>
#include <new>

namespace dqskin {
namespace {

constexpr float kInfF = std::numeric_limits<float>::infinity();

namespace fs = std::filesystem;

// The files diff compares under `root`, by relative path ('/'-separated). A symbolic link that would be
// read or walked (a link named as a baked file, or to a folder) is refused: it may name anything outside
// the folder, and its content would end up in the report.
std::map<std::string, std::string> baked_files(const std::string& root) {
  std::map<std::string, std::string> files;  // relative path → path
  std::error_code error;
  for (auto it = fs::recursive_directory_iterator(root, error); !error && it != fs::recursive_directory_iterator();
       it.increment(error)) {
    std::error_code status_error;
    const bool named = diff_detail::is_baked_file(it->path().string());
    if (it->is_symlink(status_error) && (named || it->is_directory(status_error)))
      throw InputError(it->path().string() + ": is a symbolic link, which diff does not follow in a bake folder");
    if (named && it->is_regular_file(status_error))
      files.emplace(it->path().lexically_relative(root).generic_string(), it->path().string());
  }
  if (error) throw InputError(root + ": " + error.message());
  return files;
}

// Refuses, before either is read, a pair of files whose headers declare more than --max-memory
// (`budget`) allows: A's points, then B's beside them and the errors measured.
void check_declared(const std::string& a, const std::string& b, uint64_t budget) {
  const diff_detail::DeclaredSize da = diff_detail::declared_size(a), db = diff_detail::declared_size(b);
  if (da.bytes > budget)
    throw InputError(a + ": comparing it needs about " + byte_size(da.bytes) + " (its " + da.what +
                     " as positions), more than --max-memory " + byte_size(budget));
  const uint64_t need = saturating::add(saturating::add(da.bytes, db.bytes), saturating::mul(da.points, sizeof(float)));
  if (need > budget)
    throw InputError(b + ": comparing it needs about " + byte_size(need) + " (its " + db.what + " as positions, beside " +
                     byte_size(da.bytes) + " for " + a + "), more than --max-memory " + byte_size(budget));
}

// The figures of one pair of files of the same length.
void measure(const diff_detail::BakedPoints& a, const diff_detail::BakedPoints& b, const GeometryDiffOptions& options,
             bool texels, ClipGeometryDiff& c) {
  glm::vec3 low(kInfF), high(-kInfF);
  for (const glm::vec3& p : a.positions) low = glm::min(low, p), high = glm::max(high, p);
  c.diagonal = a.positions.empty() ? 0 : double(glm::length(high - low));
  const double k = options.relative ? c.diagonal : 1.0;
  const DiffThresholds& t = options.thresholds;
  std::vector<float> errors(a.positions.size());
  double sum = 0;
  FrameDiff f;
  bool nan = false;
  for (size_t v = 0; v < errors.size(); ++v) {
    const float e = glm::length(a.positions[v] - b.positions[v]);
    errors[v] = e;
    sum += double(e);
    c.over_warn += double(e) > t.warn * k;
    c.over_fail += double(e) > t.fail * k;
    if (std::isnan(e) && !nan) nan = true, c.worst.vertex = v;
    if (!nan && double(e) > c.max_error) c.max_error = double(e), c.worst.vertex = v;
    if (v < a.normals.size() && v < b.normals.size() && glm::length(a.normals[v]) > 0 && glm::length(b.normals[v]) > 0) {
      const glm::dvec3 m = a.normals[v], n = b.normals[v];
      f.max_normal_degrees = std::max(f.max_normal_degrees, std::atan2(glm::length(glm::cross(m, n)), glm::dot(m, n)) * 180.0 / M_PI);
    }
  }
  if (nan) c.max_error = std::numeric_limits<double>::quiet_NaN();
  c.samples = errors.size();
  c.mean_error = c.samples ? sum / double(c.samples) : 0;
  if (!errors.empty()) {
    const size_t p = std::min(errors.size() - 1, size_t(std::ceil(0.99 * double(errors.size()))) - 1);
    std::nth_element(errors.begin(), errors.begin() + std::ptrdiff_t(p), errors.end());
    c.p99_error = double(errors[p]);
  }
  c.max_a_to_b = c.max_b_to_a = c.max_error;
  c.max_normal_degrees = f.max_normal_degrees;
  f.max_error = c.max_error, f.p99_error = c.p99_error, f.mean_error = c.mean_error;
  c.frames.push_back(f);
  c.status = diff_verdict({t.fail * k, t.fail_percent, t.hard_fail * k, t.warn * k, t.warn_percent, t.hard_warn * k},
                          c.max_error, c.over_warn, c.over_fail, std::max<uint64_t>(c.samples, 1));
  if (c.status == DiffStatus::kPass) return;
  const char* unit = options.relative ? " of the diagonal" : "";
  const bool failed = c.status == DiffStatus::kFail;
  const uint64_t over = failed ? c.over_fail : c.over_warn;
  c.reason = !std::isfinite(c.max_error)
                 ? "an error is not finite"
                 : std::to_string(over) + (texels ? " texels (" : " vertices (") +
                       diff_detail::percent(over, c.samples) + ") over " + (failed ? "--fail " : "--warn ") +
                       diff_detail::number(failed ? t.fail : t.warn) + unit;
}

}  // namespace

bool is_bake_folder(const std::string& path) {
  std::error_code error;
  return fs::is_directory(path, error) && fs::is_regular_file(fs::path(path) / "manifest.json", error);
}

GeometryDiffReport diff_bakes(const std::string& a, const std::string& b, const GeometryDiffOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  GeometryDiffReport report;
  report.a = a, report.b = b;
  report.bake = true;
  report.identity = true;
  report.thresholds = options.thresholds;
  report.relative = options.relative;
  const auto in_a = baked_files(a), in_b = baked_files(b);
  if (in_a.empty() && in_b.empty()) throw InputError(a + " vs " + b + ": neither folder holds a PLY, OBJ, glb or EXR file");
  std::map<std::string, bool> names;
  for (const auto& [name, path] : in_a) names[name] = true;
  for (const auto& [name, path] : in_b) names[name] = true;
  for (const auto& [name, unused] : names) {
    check_cancelled(options.cancel);
    ClipGeometryDiff c;
    c.name = c.name_b = name;
    const auto pa = in_a.find(name), pb = in_b.find(name);
    if (pa != in_a.end() && pb != in_b.end()) check_declared(pa->second, pb->second, options.load.max_memory);
    const std::string* reading = nullptr;  // for a refusal of the memory ceiling: the file being read
    try {
      if (pa == in_a.end() || pb == in_b.end()) throw InputError(pa == in_a.end() ? "missing in A" : "missing in B");
      reading = &pa->second;
      const diff_detail::BakedPoints points_a = diff_detail::read_baked_file(pa->second, options.load);
      reading = &pb->second;
      const diff_detail::BakedPoints points_b = diff_detail::read_baked_file(pb->second, options.load);
      reading = nullptr;
      if (points_a.positions.size() != points_b.positions.size())
        throw InputError(std::to_string(points_a.positions.size()) + " vertices or texels in A, " +
                         std::to_string(points_b.positions.size()) + " in B");
      measure(points_a, points_b, options, fs::path(name).extension() == ".exr", c);
      report.vertices_a += points_a.positions.size();
      report.vertices_b += points_b.positions.size();
    } catch (const InputError& e) {
      c.status = DiffStatus::kFail;
      c.reason = e.what();
    } catch (const std::bad_alloc&) {  // the pair's memory is freed by now
      const MemoryCeilingLifted lifted;
      const bool both = pa != in_a.end() && pb != in_b.end();
      throw InputError((reading ? *reading : both ? pa->second + " vs " + pb->second : name) + ": " + out_of_memory_message());
    }
    report.clips.push_back(std::move(c));
  }
  report.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace dqskin
