// Per-vertex cost of the CPU blend modes, 4 influences per vertex [Kavan §6 compares the same three].
//
// Each benchmark skins one batch of vertices per iteration: gather the vertex's 4 joints from the
// palette, blend them with the vertex's weights, and transform the position and the normal by the
// blend. The modes differ only in the blend and the transform:
//   lbs  blend_lbs of 4 Mat4; position by the matrix, normal by its upper 3×3 (not renormalised).
//   dlb  blend_dlb of 4 DualQuat; transform_point and rotate_vector.
//   dib  blend_dib with its default options (precision 1e-12, which blend_dib holds at no less than
//        16 ulps of 1, so about 1.9e-6 for float; at most 32 corrections); then as dlb.
// Every mode and precision sees the same scene: one seeded generator, drawn in double, cast to T.
//
// Counters: per_vertex (CPU time of a batch over its vertex count), items_per_second (vertices),
// and for dib the mean number of corrections per vertex (dib_iterations) and the fraction of vertices
// that ran out of iterations before reaching the precision (dib_unconverged).
#include "dqskin/dual_quat.hpp"

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

namespace {

using dqskin::DualQuat;
using dqskin::Mat3;
using dqskin::Mat4;
using dqskin::Quat;
using dqskin::Vec3;

constexpr std::size_t kVertices = 10'000;
constexpr std::size_t kJoints = 32;
constexpr std::size_t kInfluences = 4;
constexpr unsigned kSeed = 20240611;

// The joints near one vertex move together: each joint is a common rigid pose followed by a small
// relative motion (rotation up to kMaxRelativeAngle about a random axis, offset up to kMaxOffset).
constexpr double kMaxRelativeAngle = 0.5;  // radians, about 29 degrees
constexpr double kMaxOffset = 0.1;         // per axis; vertices lie within ±1
constexpr double kCommonExtent = 2.0;      // per axis, the common translation

// One skinning workload: joint palette in both representations, and the vertices with their influences.
template <typename T>
struct Scene {
  std::vector<DualQuat<T>> dual_quats;  // unit, w ≥ 0 (the sign from_rigid_matrix would give)
  std::vector<Mat4<T>> matrices;        // the same poses as rigid matrices
  std::vector<Vec3<T>> positions;
  std::vector<Vec3<T>> normals;  // unit
  std::vector<std::array<std::uint16_t, kInfluences>> joints;  // distinct joint indices per vertex
  std::vector<std::array<T, kInfluences>> weights;             // convex per vertex
};

class Random {
public:
  explicit Random(unsigned seed) : engine_(seed) {}

  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(engine_); }

  std::size_t index(std::size_t count) {
    return std::uniform_int_distribution<std::size_t>(0, count - 1)(engine_);
  }

  glm::dvec3 vec3(double extent) {
    return {uniform(-extent, extent), uniform(-extent, extent), uniform(-extent, extent)};
  }

  glm::dvec3 unit_vec3() {
    // Uniform on the sphere: z uniform in [-1, 1], azimuth uniform.
    const double z = uniform(-1, 1), phi = uniform(0, 2 * std::numbers::pi);
    const double s = std::sqrt(1 - z * z);
    return {s * std::cos(phi), s * std::sin(phi), z};
  }

  // Uniformly distributed unit quaternion (Shoemake's subgroup algorithm).
  glm::dquat rotation() {
    const double u1 = uniform(0, 1), u2 = uniform(0, 2 * std::numbers::pi), u3 = uniform(0, 2 * std::numbers::pi);
    const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    return glm::dquat(a * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3));  // w, x, y, z
  }

private:
  std::mt19937_64 engine_;
};

template <typename T>
Scene<T> make_scene() {
  Random random(kSeed);
  Scene<T> scene;

  const glm::dquat common_rotation = random.rotation();
  const glm::dvec3 common_translation = random.vec3(kCommonExtent);
  for (std::size_t j = 0; j < kJoints; ++j) {
    const glm::dquat relative =
        glm::angleAxis(random.uniform(0, kMaxRelativeAngle), random.unit_vec3());
    glm::dquat r = glm::normalize(common_rotation * relative);
    if (r.w < 0) r = -r;
    const glm::dvec3 t = common_translation + random.vec3(kMaxOffset);

    const Quat<T> rt(r);
    const Vec3<T> tt(t);
    scene.dual_quats.push_back(DualQuat<T>(rt, tt));  // GLM: real = r, dual = 0.5 (0, t) r
    Mat4<T> m = glm::mat4_cast(rt);
    m[3] = glm::vec<4, T, glm::defaultp>(tt, T(1));
    scene.matrices.push_back(m);
  }

  for (std::size_t v = 0; v < kVertices; ++v) {
    scene.positions.push_back(Vec3<T>(random.vec3(1)));
    scene.normals.push_back(Vec3<T>(random.unit_vec3()));

    // Distinct joints: the first kInfluences of a partial Fisher-Yates shuffle.
    std::array<std::uint16_t, kJoints> order{};
    for (std::size_t j = 0; j < kJoints; ++j) order[j] = static_cast<std::uint16_t>(j);
    std::array<std::uint16_t, kInfluences> joints{};
    for (std::size_t k = 0; k < kInfluences; ++k) {
      std::swap(order[k], order[k + random.index(kJoints - k)]);
      joints[k] = order[k];
    }
    scene.joints.push_back(joints);

    std::array<double, kInfluences> w{};
    double sum = 0;
    for (double& x : w) sum += (x = random.uniform(0, 1));
    std::array<T, kInfluences> weights{};
    for (std::size_t k = 0; k < kInfluences; ++k) weights[k] = static_cast<T>(w[k] / sum);
    scene.weights.push_back(weights);
  }
  return scene;
}

enum class Mode { lbs, dlb, dib };

// Skins every vertex of the scene once per iteration and reports the cost per vertex.
template <typename T, Mode mode>
void bm_blend(benchmark::State& state) {
  const Scene<T> scene = make_scene<T>();
  std::vector<Vec3<T>> out_positions(kVertices);
  std::vector<Vec3<T>> out_normals(kVertices);
  std::int64_t dib_iterations = 0;
  std::int64_t dib_unconverged = 0;

  for ([[maybe_unused]] auto _ : state) {
    for (std::size_t v = 0; v < kVertices; ++v) {
      const std::array<std::uint16_t, kInfluences>& joints = scene.joints[v];
      const std::array<T, kInfluences>& weights = scene.weights[v];
      if constexpr (mode == Mode::lbs) {
        std::array<Mat4<T>, kInfluences> m;
        for (std::size_t k = 0; k < kInfluences; ++k) m[k] = scene.matrices[joints[k]];
        const Mat4<T> b = dqskin::blend_lbs<T>(m, weights);
        out_positions[v] = Vec3<T>(b * glm::vec<4, T, glm::defaultp>(scene.positions[v], T(1)));
        out_normals[v] = Mat3<T>(b) * scene.normals[v];
      } else {
        std::array<DualQuat<T>, kInfluences> q;
        for (std::size_t k = 0; k < kInfluences; ++k) q[k] = scene.dual_quats[joints[k]];
        DualQuat<T> b;
        if constexpr (mode == Mode::dlb) {
          b = dqskin::blend_dlb<T>(q, weights);
        } else {
          const dqskin::DibResult<T> result = dqskin::blend_dib<T>(q, weights);
          b = result.blend;
          dib_iterations += result.iterations;
          dib_unconverged += result.converged ? 0 : 1;
        }
        out_positions[v] = dqskin::transform_point(b, scene.positions[v]);
        out_normals[v] = dqskin::rotate_vector(b, scene.normals[v]);
      }
    }
    benchmark::DoNotOptimize(out_positions.data());
    benchmark::DoNotOptimize(out_normals.data());
    benchmark::ClobberMemory();
  }

  const auto vertices = static_cast<std::int64_t>(kVertices);
  state.SetItemsProcessed(state.iterations() * vertices);
  // Inverted iteration-invariant rate: CPU time / (iterations × vertices), in seconds per vertex; the
  // console prints it with an SI prefix ("25.5ns").
  state.counters["per_vertex"] = benchmark::Counter(
      static_cast<double>(kVertices), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  if constexpr (mode == Mode::dib) {
    const double blends = static_cast<double>(state.iterations() * vertices);
    state.counters["dib_iterations"] = static_cast<double>(dib_iterations) / blends;
    state.counters["dib_unconverged"] = static_cast<double>(dib_unconverged) / blends;
  }
}

// Registered in table order: the three modes side by side, float then double.
BENCHMARK(bm_blend<float, Mode::lbs>)->Name("blend/lbs/float")->Unit(benchmark::kMicrosecond);
BENCHMARK(bm_blend<float, Mode::dlb>)->Name("blend/dlb/float")->Unit(benchmark::kMicrosecond);
BENCHMARK(bm_blend<float, Mode::dib>)->Name("blend/dib/float")->Unit(benchmark::kMicrosecond);
BENCHMARK(bm_blend<double, Mode::lbs>)->Name("blend/lbs/double")->Unit(benchmark::kMicrosecond);
BENCHMARK(bm_blend<double, Mode::dlb>)->Name("blend/dlb/double")->Unit(benchmark::kMicrosecond);
BENCHMARK(bm_blend<double, Mode::dib>)->Name("blend/dib/double")->Unit(benchmark::kMicrosecond);

}  // namespace
