// The shader kits' math against the C++ decode: glslangValidator only type-checks the kits (kits.compile),
// so here the Godot kit's functions (glsl/kits/godot/dqskin.gdshaderinc, as the bake embeds it; the HLSL
// kit is the same formulas term for term) run in a compute shader on a headless GL context and are compared
// with the decode-back check's CPU model of each layout (lib/texture/bone_profiles.hpp skin_vertex) and with
// the formulas of docs/formats.md, "Shader kits": clip table, VAT interpolation, crossfades, sockets.
#include "shader_kit.hpp"

#include "../gpu/gl_functions.hpp"
#include "../gpu/shader_program.hpp"
#include "../math/test_support.hpp"
#include "../test_support/gpu_context.hpp"
#include "../texture/bone_profiles.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

namespace dqskin::kit {
namespace {

using Vec4 = std::array<float, 4>;

std::string godot_functions() {
  for (const KitFile& file : shader_kit_files({"godot"}))
    if (file.path.ends_with("dqskin.gdshaderinc")) return std::string(file.bytes);
  ADD_FAILURE() << "no godot/dqskin.gdshaderinc in the kit";
  return {};
}

// Runs `body` (GLSL statements; `i` the item, `inputs[]` and `outputs[]` vec4 arrays, `image` an RGBA32F
// texture read with texelFetch) once per item, with the kit's functions in scope. Returns the outputs.
std::vector<Vec4> run_kit(GpuContext& context, const std::string& body, const std::vector<Vec4>& inputs,
                          size_t items, size_t outputs_per_item, const std::vector<float>& image, int width,
                          int height) {
  context.make_current();
  gpu::Gl gl;
  EXPECT_EQ(gl.load(context), "");
  const std::string text = "layout(local_size_x = 1) in;\n"
                           "layout(std430, binding = 0) readonly buffer Inputs { vec4 inputs[]; };\n"
                           "layout(std430, binding = 1) writeonly buffer Outputs { vec4 outputs[]; };\n"
                           "uniform sampler2D image;\n" +
                           godot_functions() + "\nvoid main() {\n  int i = int(gl_GlobalInvocationID.x);\n" + body + "\n}\n";
  const gpu::ShaderSource source{"glsl/kits/godot/dqskin.gdshaderinc (test)", text.c_str()};
  const GLuint program = gpu::build_program(gl, {{GL_COMPUTE_SHADER, source}}, "");
  GLuint texture = 0, buffers[2] = {0, 0};
  gl.GenTextures(1, &texture);
  gl.ActiveTexture(GL_TEXTURE0);
  gl.BindTexture(GL_TEXTURE_2D, texture);
  gl.TexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, width, height);
  gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, image.data());
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.GenBuffers(2, buffers);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[0]);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(std::max<size_t>(inputs.size(), 1) * sizeof(Vec4)),
                inputs.empty() ? nullptr : inputs.data(), GL_STATIC_DRAW);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
  std::vector<Vec4> outputs(items * outputs_per_item);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[1]);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(outputs.size() * sizeof(Vec4)), nullptr, GL_DYNAMIC_READ);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
  gl.UseProgram(program);
  gl.Uniform1i(gl.GetUniformLocation(program, "image"), 0);
  gl.DispatchCompute(GLuint(items), 1, 1);
  gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(outputs.size() * sizeof(Vec4)), outputs.data());
  EXPECT_EQ(gl.GetError(), GLenum(GL_NO_ERROR));
  gl.DeleteBuffers(2, buffers);
  gl.DeleteTextures(1, &texture);
  gl.DeleteProgram(program);
  return outputs;
}

Vec3<double> xyz(const Vec4& v) { return {v[0], v[1], v[2]}; }

// |q · r| for a unit quaternion r read back and q: 1 when they are the same rotation (either sign).
double same_rotation(const Vec4& r, const DualQuat<double>& q) {
  return std::abs(double(r[0]) * q.real.x + double(r[1]) * q.real.y + double(r[2]) * q.real.z + double(r[3]) * q.real.w);
}

double distance(const Vec3<double>& a, const Vec3<double>& b) { return glm::length(a - b); }

Vec3<double> unit(const Vec3<double>& v) { return glm::length(v) > 0 ? v / glm::length(v) : v; }

// One skin's joints over `frames` frames: random rigid poses, with scale and shear when `scaled`.
std::vector<JointTransforms> random_frames(test::Random& random, size_t joints, size_t frames, bool scaled) {
  std::vector<JointTransforms> out(frames);
  for (JointTransforms& f : out) {
    for (size_t j = 0; j < joints; ++j) {
      const DualQuat<double> q = random.pose(2.0);
      Mat3<double> s(1.0);
      if (scaled)
        for (int a = 0; a < 3; ++a)
          for (int b = a; b < 3; ++b) s[a][b] = s[b][a] = (a == b ? 1.0 : 0.0) + random.uniform(-0.2, 0.2);
      Mat4<double> m = to_rigid_matrix(q);
      const Mat3<double> a = Mat3<double>(m) * s;
      for (int c = 0; c < 3; ++c) m[c] = glm::dvec4(a[c], 0.0);
      f.matrices.push_back(m);
      f.rigid.push_back(q);
      f.scale.push_back(s);
    }
    f.any_non_rigid = scaled;
  }
  return out;
}

// Up to eight influences; with four, the last four have no weight.
struct Vertex {
  std::array<int, 8> joints{};
  std::array<float, 8> weights{};
  Vec3<double> position, normal;
};

std::vector<Vertex> random_vertices(test::Random& random, size_t count, size_t joints, int influences = 4) {
  std::vector<Vertex> out(count);
  for (Vertex& v : out) {
    for (int k = 0; k < influences; ++k) {
      v.joints[size_t(k)] = int(random.uniform(0, double(joints) - 1e-9));
      v.weights[size_t(k)] = random.uniform(0, 1) < 0.2 ? 0.0f : float(random.uniform(0.05, 1));
    }
    v.position = random.vec3(1.5);
    v.normal = unit(random.vec3(1.0));
  }
  return out;
}

// The skin functions of the kit on `image`, from row_a to row_b by `blend`, for every vertex.
// With eight influences through the functions' 8 variants, else the four-influence ones.
std::vector<SkinnedVertex> kit_skin(GpuContext& context, const BoneImage& image, const std::vector<Vertex>& vertices,
                                    float row_a, float row_b, float blend, int influences = 4) {
  std::vector<Vec4> inputs;
  for (const Vertex& v : vertices) {
    for (int set = 0; set < 2; ++set) {
      const size_t k = size_t(4 * set);
      inputs.push_back({float(v.joints[k]), float(v.joints[k + 1]), float(v.joints[k + 2]), float(v.joints[k + 3])});
      inputs.push_back({v.weights[k], v.weights[k + 1], v.weights[k + 2], v.weights[k + 3]});
    }
    inputs.push_back({float(v.position.x), float(v.position.y), float(v.position.z), 0.0f});
    inputs.push_back({float(v.normal.x), float(v.normal.y), float(v.normal.z), 0.0f});
  }
  const bool dq = image.profile == BoneProfile::kDq;
  const std::string call = std::string(dq ? "dqskin_dq_skin" : "dqskin_matrix_skin") +
                           (influences == 8 ? "8(image, " : "(image, ") + std::to_string(image.texels_per_joint) +
                           ".0, inputs[6 * i], inputs[6 * i + 1], " +
                           (influences == 8 ? "inputs[6 * i + 2], inputs[6 * i + 3], " : "") + std::to_string(row_a) +
                           ", " + std::to_string(row_b) + ", " + std::to_string(blend) +
                           ", inputs[6 * i + 4].xyz, inputs[6 * i + 5].xyz, p, n);";
  const std::vector<Vec4> out = run_kit(context, "  vec3 p;\n  vec3 n;\n  " + call +
                                                     "\n  outputs[2 * i] = vec4(p, 1.0);\n  outputs[2 * i + 1] = vec4(n, 0.0);",
                                        inputs, vertices.size(), 2, image.rgba, int(image.width), int(image.height));
  std::vector<SkinnedVertex> skinned;
  for (size_t i = 0; i < vertices.size(); ++i) skinned.push_back({xyz(out[2 * i]), unit(xyz(out[2 * i + 1]))});
  return skinned;
}

SkinnedVertex cpu_skin(const BoneImage& image, size_t frame, const Vertex& v) {
  return skin_vertex(image, frame, v.joints, v.weights, v.position, v.normal);
}

// float on the GPU against double: positions within 2 µm of units of 1 to 4, normals within 1e-5.
constexpr double kPositionTolerance = 2e-5, kNormalTolerance = 1e-5;

struct ProfileCase {
  BoneProfile profile;
  bool scaled;
  int influences;
};

class KitSkin : public testing::TestWithParam<ProfileCase> {};

TEST_P(KitSkin, MatchesTheCpuDecodeAndCrossfadesBetweenRows) {
  const auto context = testing_support::context_or_null();
  if (!context) GTEST_SKIP() << "no OpenGL 4.3 context";
  test::Random random(7);
  const std::vector<JointTransforms> frames = random_frames(random, 6, 3, GetParam().scaled);
  const BoneImage image = pack_bones(GetParam().profile, frames);
  ASSERT_EQ(image.texels_per_joint, GetParam().profile == BoneProfile::kDq ? (GetParam().scaled ? 5 : 2)
                                    : GetParam().profile == BoneProfile::kMat3x4 ? 3 : 4);
  const int influences = GetParam().influences;
  const std::vector<Vertex> vertices = random_vertices(random, 256, 6, influences);
  // Each row alone, then crossfades at their ends: blend 0 is row A, blend 1 row B.
  for (const auto& [row_a, row_b, blend, expected_row] :
       std::vector<std::tuple<int, int, float, size_t>>{{0, 0, 0.0f, 0}, {2, 2, 0.0f, 2}, {1, 2, 0.0f, 1}, {0, 2, 1.0f, 2}}) {
    const std::vector<SkinnedVertex> gpu = kit_skin(*context, image, vertices, float(row_a), float(row_b), blend, influences);
    double worst_p = 0, worst_n = 0;
    for (size_t i = 0; i < vertices.size(); ++i) {
      const SkinnedVertex cpu = cpu_skin(image, expected_row, vertices[i]);
      worst_p = std::max(worst_p, distance(gpu[i].position, cpu.position));
      worst_n = std::max(worst_n, distance(gpu[i].normal, cpu.normal));
    }
    std::printf("%s%s, %d influences, rows %d to %d by %.1f: largest position difference %.3g, normal %.3g\n", to_string(GetParam().profile),
                GetParam().scaled ? " (scaled)" : "", influences, row_a, row_b, double(blend), worst_p, worst_n);
    EXPECT_LT(worst_p, kPositionTolerance) << "rows " << row_a << " to " << row_b << " by " << blend;
    EXPECT_LT(worst_n, kNormalTolerance) << "rows " << row_a << " to " << row_b << " by " << blend;
  }
}

INSTANTIATE_TEST_SUITE_P(Profiles, KitSkin,
                         testing::Values(ProfileCase{BoneProfile::kDq, false, 4}, ProfileCase{BoneProfile::kDq, true, 4},
                                         ProfileCase{BoneProfile::kMat3x4, false, 4}, ProfileCase{BoneProfile::kMat4, true, 4},
                                         ProfileCase{BoneProfile::kDq, true, 8}, ProfileCase{BoneProfile::kMat4, false, 8}),
                         [](const testing::TestParamInfo<ProfileCase>& param_info) {
                           std::string name = to_string(param_info.param.profile);
                           std::erase(name, '-');
                           return name + (param_info.param.scaled ? "_scaled" : "") + "_" +
                                  std::to_string(param_info.param.influences);
                         });

// Halfway between two rows: the dq kit blends each joint (docs/DESIGN.md §3.10: B into A's hemisphere, real
// and dual lerped and normalized, S lerped) before DLB; that equals the CPU decode of an image whose row
// holds those blended texels. The matrix kit
// lerps the matrices: the CPU decode of the lerped row.
TEST(KitSkin, CrossfadeHalfwayIsTheDecodeOfTheBlendedJoints) {
  const auto context = testing_support::context_or_null();
  if (!context) GTEST_SKIP() << "no OpenGL 4.3 context";
  test::Random random(11);
  for (const BoneProfile profile : {BoneProfile::kDq, BoneProfile::kMat4}) {
    const std::vector<JointTransforms> frames = random_frames(random, 5, 2, true);
    const BoneImage image = pack_bones(profile, frames);
    BoneImage blended = image;
    blended.frames = blended.height = 1;
    blended.rgba.resize(image.width * 4);
    const size_t t = size_t(image.texels_per_joint);
    for (size_t j = 0; j < image.joints; ++j) {
      const float* a = &image.rgba[4 * t * j];
      const float* b = &image.rgba[4 * (image.width + t * j)];
      float sign = 1.0f;
      if (profile == BoneProfile::kDq && a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] < 0) sign = -1.0f;
      float* out = &blended.rgba[4 * t * j];
      for (size_t c = 0; c < 4 * t; ++c) out[c] = 0.5f * a[c] + 0.5f * (profile == BoneProfile::kDq && c < 8 ? sign : 1.0f) * b[c];
      if (profile == BoneProfile::kDq) {  // a unit dual quaternion: real of length 1, dual orthogonal to it
        const float length = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2] + out[3] * out[3]);
        for (size_t c = 0; c < 8; ++c) out[c] /= length;
        const float along = out[0] * out[4] + out[1] * out[5] + out[2] * out[6] + out[3] * out[7];
        for (size_t c = 0; c < 4; ++c) out[4 + c] -= along * out[c];
      }
    }
    const std::vector<Vertex> vertices = random_vertices(random, 128, 5);
    const std::vector<SkinnedVertex> gpu = kit_skin(*context, image, vertices, 0.0f, 1.0f, 0.5f);
    double worst_p = 0, worst_n = 0;
    for (size_t i = 0; i < vertices.size(); ++i) {
      const SkinnedVertex cpu = cpu_skin(blended, 0, vertices[i]);
      worst_p = std::max(worst_p, distance(gpu[i].position, cpu.position));
      worst_n = std::max(worst_n, distance(gpu[i].normal, cpu.normal));
    }
    EXPECT_LT(worst_p, kPositionTolerance) << to_string(profile);
    EXPECT_LT(worst_n, kNormalTolerance) << to_string(profile);
  }
}

// The dqskin VAT: vertex v of frame f at (v % W, f R + v / W); between frames the neighbours lerped, never
// past the clip's last frame; a crossfade lerps the two clips' positions and renormalizes the normals.
TEST(KitVat, InterpolatesFramesAndCrossfades) {
  const auto context = testing_support::context_or_null();
  if (!context) GTEST_SKIP() << "no OpenGL 4.3 context";
  test::Random random(3);
  const int width = 4, rows = 2, frames = 3, vertices = 7;
  std::vector<float> positions(size_t(width * rows * frames * 4)), normals(positions.size());
  for (float& x : positions) x = float(random.uniform(-3, 3));
  auto texel = [&](int v, int f) { return size_t(4 * ((f * rows + v / width) * width + v % width)); };
  std::vector<Vec4> inputs;
  for (int v = 0; v < vertices; ++v) inputs.push_back({float(v % width), float(v / width), 0.0f, 0.0f});
  // positions as both textures: the normal path is the same read, then normalized.
  const std::vector<Vec4> out = run_kit(
      *context,
      "  vec3 p0, n0, p1, n1, p2, n2;\n"
      "  dqskin_vat(image, image, inputs[i].xy, 1.25, 2.0, 2.0, p0, n0);\n"
      "  dqskin_vat(image, image, inputs[i].xy, 2.5, 2.0, 2.0, p1, n1);\n"
      "  dqskin_vat_crossfade(image, image, inputs[i].xy, 0.5, 2.0, 1.25, 2.0, 0.25, 2.0, p2, n2);\n"
      "  outputs[4 * i] = vec4(p0, 0.0); outputs[4 * i + 1] = vec4(p1, 0.0); outputs[4 * i + 2] = vec4(p2, 0.0);\n"
      "  outputs[4 * i + 3] = vec4(n2, 0.0);",
      inputs, size_t(vertices), 4, positions, width, rows * frames);
  for (int v = 0; v < vertices; ++v) {
    auto at = [&](int f) { return Vec3<double>(positions[texel(v, f)], positions[texel(v, f) + 1], positions[texel(v, f) + 2]); };
    const Vec3<double> frame_1_25 = glm::mix(at(1), at(2), 0.25), frame_0_5 = glm::mix(at(0), at(1), 0.5);
    EXPECT_LT(distance(xyz(out[size_t(4 * v)]), frame_1_25), 1e-5) << v;
    EXPECT_LT(distance(xyz(out[size_t(4 * v + 1)]), at(2)), 1e-5) << v;  // clamped at the last frame
    const Vec3<double> fade = glm::mix(frame_0_5, frame_1_25, 0.25);
    EXPECT_LT(distance(xyz(out[size_t(4 * v + 2)]), fade), 1e-5) << v;
    EXPECT_LT(distance(xyz(out[size_t(4 * v + 3)]), unit(glm::mix(unit(frame_0_5), unit(frame_1_25), 0.25))), 1e-5) << v;
  }
}

// Sockets: texels 5s + 0..2 the matrix rows, 5s + 3 and 5s + 4 the dual quaternion; at a frame the kit
// returns that frame's pose, between frames the DLB of the two (normalized), matrices lerped.
TEST(KitSockets, PoseAtAndBetweenFrames) {
  const auto context = testing_support::context_or_null();
  if (!context) GTEST_SKIP() << "no OpenGL 4.3 context";
  test::Random random(5);
  const int sockets = 3, frames = 4, width = 5 * sockets;
  std::vector<DualQuat<double>> poses;
  std::vector<float> image(size_t(width * frames * 4));
  for (int f = 0; f < frames; ++f)
    for (int s = 0; s < sockets; ++s) {
      const DualQuat<double> q = random.pose(3.0);
      poses.push_back(q);
      const Mat4<double> m = to_rigid_matrix(q);
      float* t = &image[size_t(4 * (f * width + 5 * s))];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) t[4 * r + c] = float(m[c][r]);
      const double parts[8] = {q.real.x, q.real.y, q.real.z, q.real.w, q.dual.x, q.dual.y, q.dual.z, q.dual.w};
      for (int k = 0; k < 8; ++k) t[12 + k] = float(parts[k]);
    }
  std::vector<Vec4> inputs;
  for (int s = 0; s < sockets; ++s) inputs.push_back({float(s), 0.0f, 0.0f, 0.0f});
  const std::vector<Vec4> out = run_kit(
      *context,
      "  vec3 p0, p1; vec4 r0, r1, m0, m1, m2;\n"
      "  dqskin_socket(image, inputs[i].x, 2.0, 3.0, p0, r0);\n"
      "  dqskin_socket(image, inputs[i].x, 0.5, 3.0, p1, r1);\n"
      "  dqskin_socket_matrix(image, inputs[i].x, 0.5, 3.0, m0, m1, m2);\n"
      "  outputs[7 * i] = vec4(p0, 0.0); outputs[7 * i + 1] = r0; outputs[7 * i + 2] = vec4(p1, 0.0);\n"
      "  outputs[7 * i + 3] = r1; outputs[7 * i + 4] = m0; outputs[7 * i + 5] = m1; outputs[7 * i + 6] = m2;",
      inputs, size_t(sockets), 7, image, width, frames);
  for (int s = 0; s < sockets; ++s) {
    const DualQuat<double>& at2 = poses[size_t(2 * sockets + s)];
    const auto o = [&](int k) { return out[size_t(7 * s + k)]; };
    EXPECT_LT(distance(xyz(o(0)), translation(at2)), 1e-5) << s;
    EXPECT_NEAR(same_rotation(o(1), at2), 1.0, 1e-6) << s;
    const DualQuat<double> q[2] = {poses[size_t(s)], poses[size_t(sockets + s)]};
    const double w[2] = {0.5, 0.5};
    const DualQuat<double> half = blend_dlb<double>(q, w);
    EXPECT_LT(distance(xyz(o(2)), translation(half)), 1e-5) << s;
    EXPECT_NEAR(same_rotation(o(3), half), 1.0, 1e-6) << s;
    const Mat4<double> m0 = to_rigid_matrix(q[0]), m1 = to_rigid_matrix(q[1]);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(o(4 + r)[size_t(c)], 0.5 * (m0[c][r] + m1[c][r]), 1e-5) << s;
  }
}

// The clip table: first_frame + time · fps, clamped, or wrapped with period frame_count − 1 when looping.
TEST(KitClipTable, FrameOfATime) {
  const auto context = testing_support::context_or_null();
  if (!context) GTEST_SKIP() << "no OpenGL 4.3 context";
  // time, first_frame, frame_count, fps; loop in the second output's use below.
  const std::vector<Vec4> inputs = {{0.5f, 10.0f, 5.0f, 4.0f}, {2.0f, 10.0f, 5.0f, 4.0f}, {1.25f, 10.0f, 5.0f, 4.0f},
                                    {-0.25f, 10.0f, 5.0f, 4.0f}, {3.0f, 7.0f, 1.0f, 30.0f}};
  const std::vector<Vec4> out = run_kit(*context,
                                        "  float f, l, g, m;\n"
                                        "  dqskin_clip_frame(inputs[i].x, inputs[i].y, inputs[i].z, inputs[i].w, 0.0, f, l);\n"
                                        "  dqskin_clip_frame(inputs[i].x, inputs[i].y, inputs[i].z, inputs[i].w, 1.0, g, m);\n"
                                        "  outputs[i] = vec4(f, l, g, m);",
                                        inputs, inputs.size(), 1, std::vector<float>(4, 0.0f), 1, 1);
  const std::vector<Vec4> expected = {{12, 14, 12, 14}, {14, 14, 10, 14}, {14, 14, 11, 14}, {10, 14, 13, 14}, {7, 7, 7, 7}};
  for (size_t i = 0; i < inputs.size(); ++i)
    for (size_t k = 0; k < 4; ++k) EXPECT_NEAR(out[i][k], expected[i][k], 1e-5) << "case " << i << ", output " << k;
}

}  // namespace
}  // namespace dqskin::kit
