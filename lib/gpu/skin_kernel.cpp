// The "deform" stage on the GPU: rest data in SSBOs, one BoneTexture per instance and batch, glsl/skin.comp
// dispatched over (vertices, frames of the batch).
#include "skin_kernel.hpp"

#include "dqskin/error.hpp"
#include "gl_functions.hpp"
#include "shader_program.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <map>
#include <stdexcept>
#include <tuple>

namespace dqskin::gpu {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// What one compiled variant of skin.comp is specialised for.
struct Variant {
  BlendMode mode;
  int texels, influences, targets;
  bool normals, tangents;
  auto key() const { return std::tie(mode, texels, influences, targets, normals, tangents); }
  bool operator<(const Variant& o) const { return key() < o.key(); }
};

// skin.comp specialised for one variant (docs/DESIGN.md §4.1: texels per joint, influences, morph targets).
GLuint compile_program(const Gl& gl, const Variant& v) {
  std::string defines = v.mode == BlendMode::kLbs ? "#define MODE_LBS\n" : "#define MODE_DQS\n";
  defines += "#define TEXELS " + std::to_string(v.texels) + "\n";
  defines += "#define INFLUENCES " + std::to_string(v.influences) + "\n";
  defines += "#define MORPH_TARGETS " + std::to_string(v.targets) + "\n";
  if (v.normals) defines += "#define HAS_NORMALS\n";
  if (v.tangents) defines += "#define HAS_TANGENTS\n";
  return build_program(gl, {{GL_COMPUTE_SHADER, kSkinComp}}, defines);
}

template <typename T>
GLuint make_buffer(const Gl& gl, const std::vector<T>& data, size_t bytes_if_empty = 16) {
  GLuint b = 0;
  gl.GenBuffers(1, &b);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, b);
  const size_t bytes = data.empty() ? bytes_if_empty : data.size() * sizeof(T);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(bytes), data.empty() ? nullptr : data.data(), GL_STATIC_DRAW);
  return b;
}

}  // namespace

struct SkinKernel::Impl {
  struct Prim {
    size_t instance = 0;  // index into instances
    size_t vertices = 0;
    int influences = 4;
    int targets = 0;
    bool normals = false, tangents = false;
    GLuint rest_position = 0, rest_normal = 0, rest_tangent = 0, influence = 0, morph_offset = 0;
    GLuint morph_weight = 0;
    // Two sets of outputs: batch b is computed into set b % 2 while batch b − 1 is read from the other.
    GLuint out_position[2] = {}, out_normal[2] = {}, out_tangent[2] = {};
    // With mapped readback, where each output buffer is mapped for the kernel's life.
    const float* mapped_position[2] = {}, *mapped_normal[2] = {}, *mapped_tangent[2] = {};
  };

  GpuContext& context;
  Gl gl;
  const Asset& asset;
  std::vector<MeshInstance> instances;
  BlendMode mode;
  size_t memory_budget;
  std::vector<Prim> prims;
  std::map<Variant, GLuint> programs;
  std::vector<GLuint> textures;  // one per instance
  size_t batch = 1;

  GLint max_texture_width = 0;  // GL_MAX_TEXTURE_SIZE, asked once by the constructor

  bool mapped = false;  // outputs read through persistently mapped buffers

  Impl(GpuContext& c, const Asset& a, std::vector<MeshInstance> inst, BlendMode m, size_t budget, bool mapped_readback)
      : context(c), asset(a), instances(std::move(inst)), mode(m), memory_budget(budget) {
    if (!has_gpu_path(mode))
      throw InputError("mode dib runs on the CPU reference only; the GPU path offers lbs and dqs");
    context.make_current();
    if (const std::string missing = gl.load(context); !missing.empty())
      throw NoGpuContext("the OpenGL context has no " + missing);
    mapped = mapped_readback && gl.BufferStorage;
    check_texture_width();
    upload();
    choose_batch();
    textures.assign(instances.size(), 0);
  }

  ~Impl() {
    context.make_current();
    for (Prim& p : prims) {
      const GLuint b[] = {p.rest_position, p.rest_normal, p.rest_tangent, p.influence, p.morph_offset, p.morph_weight,
                          p.out_position[0], p.out_normal[0], p.out_tangent[0],
                          p.out_position[1], p.out_normal[1], p.out_tangent[1]};
      gl.DeleteBuffers(GLsizei(std::size(b)), b);
    }
    for (GLuint t : textures)
      if (t) gl.DeleteTextures(1, &t);
    for (auto& [variant, program] : programs) gl.DeleteProgram(program);
  }

  // A skin's bone texture is at least 2 texels a joint wide (docs/DESIGN.md §4.1): one wider than
  // the GPU's largest texture is refused now, before the caller has written anything, not at the first batch.
  void check_texture_width() {
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture_width);
    for (const MeshInstance& inst : instances) {
      if (inst.skin < 0) continue;
      const size_t joints = asset.skins[size_t(inst.skin)].joints.size();
      if (joints * 2 > size_t(max_texture_width))
        throw InputError("skin " + std::to_string(inst.skin) + " has " + std::to_string(joints) +
                         " joints: its bone texture needs at least " + std::to_string(joints * 2) +
                         " texels a row, and this GPU allows " + std::to_string(max_texture_width));
    }
  }

  void upload() {
    for (size_t i = 0; i < instances.size(); ++i) {
      const MeshInstance& inst = instances[i];
      for (const Primitive& src : asset.meshes[size_t(inst.mesh)].primitives) {
        Prim p;
        p.instance = i;
        p.vertices = src.vertex_count();
        p.normals = !src.normals.empty();
        p.tangents = !src.tangents.empty();
        p.targets = int(src.targets.size());
        const bool skinned = inst.skin >= 0;
        p.influences = skinned ? src.influences : 4;  // a rigid instance: one joint, its node, weight 1
        // skin.comp takes any multiple of 4 (INFLUENCES); the Asset holds at most kMaxInfluences (asset.hpp).
        if (p.influences > kMaxInfluences)
          throw std::invalid_argument("SkinKernel: more than kMaxInfluences influences per vertex");

        std::vector<float> pos(p.vertices * 3), nrm, offsets;
        for (size_t v = 0; v < p.vertices; ++v)
          for (int c = 0; c < 3; ++c) pos[v * 3 + size_t(c)] = src.positions[v][c];
        if (p.normals) {
          nrm.resize(p.vertices * 3);
          for (size_t v = 0; v < p.vertices; ++v)
            for (int c = 0; c < 3; ++c) nrm[v * 3 + size_t(c)] = src.normals[v][c];
        }
        std::vector<glm::vec4> tan(src.tangents.begin(), src.tangents.end());
        // Influence records: K/2 packed joint pairs, then K weights (as uint bits).
        const size_t k = size_t(p.influences);
        std::vector<uint32_t> infl(p.vertices * (k + k / 2), 0);
        for (size_t v = 0; v < p.vertices; ++v) {
          uint32_t* rec = &infl[v * (k + k / 2)];
          for (size_t j = 0; j < k; ++j) {
            const uint32_t joint = skinned ? src.joints[v * k + j] : 0;
            const float weight = skinned ? src.weights[v * k + j] : (j == 0 ? 1.0f : 0.0f);
            rec[j / 2] |= joint << (16 * (j % 2));
            std::memcpy(&rec[k / 2 + j], &weight, 4);
          }
        }
        // Morph offsets: positions of every target, then normals, then tangents (zeros where absent).
        if (p.targets) {
          const size_t t = size_t(p.targets), n = p.vertices;
          offsets.assign(3 * t * n * 3, 0.0f);
          for (size_t m = 0; m < t; ++m) {
            const MorphTarget& target = src.targets[m];
            const std::vector<glm::vec3>* parts[3] = {&target.positions, &target.normals, &target.tangents};
            for (size_t part = 0; part < 3; ++part)
              for (size_t v = 0; v < parts[part]->size(); ++v)
                for (int c = 0; c < 3; ++c) offsets[((part * t + m) * n + v) * 3 + size_t(c)] = (*parts[part])[v][c];
          }
        }
        p.rest_position = make_buffer(gl, pos);
        p.rest_normal = make_buffer(gl, nrm);
        p.rest_tangent = make_buffer(gl, tan);
        p.influence = make_buffer(gl, infl);
        p.morph_offset = make_buffer(gl, offsets);
        p.morph_weight = make_buffer(gl, std::vector<float>{});
        prims.push_back(p);
      }
    }
  }

  size_t bytes_per_frame(const Prim& p) const {
    return p.vertices * (12u + (p.normals ? 12u : 0u) + (p.tangents ? 16u : 0u));
  }

  void choose_batch() {
    GLint max_block = 0, max_rows = 0, max_groups_y = 0;
    gl.GetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_rows);
    gl.GetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 1, &max_groups_y);
    size_t total = 0;
    batch = size_t(std::min(max_rows, max_groups_y));
    for (const Prim& p : prims) {
      total += bytes_per_frame(p);
      // Each output array is one SSBO binding: llvmpipe caps a binding at 128 MiB.
      batch = std::min(batch, size_t(max_block) / std::max<size_t>(1, p.vertices * 16));
    }
    // Two batches are in flight (one computed, one read back), so the budget holds two sets of outputs.
    batch = std::min(batch, memory_budget / std::max<size_t>(1, 2 * total));
    batch = std::max<size_t>(batch, 1);
    for (Prim& p : prims) {
      auto out = [&](size_t per_vertex, const float*& pointer) {
        GLuint b = 0;
        gl.GenBuffers(1, &b);
        gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, b);
        const GLsizeiptr bytes = GLsizeiptr(std::max<size_t>(16, p.vertices * per_vertex * batch));
        if (!mapped) {
          gl.BufferData(GL_SHADER_STORAGE_BUFFER, bytes, nullptr, GL_DYNAMIC_READ);
          return b;
        }
        // Mapped once, coherent: after a batch's fence the host reads what the shader wrote, with no map
        // or copy call per batch. CLIENT_STORAGE asks for memory the CPU reads fast (host memory).
        const GLbitfield access = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
        gl.BufferStorage(GL_SHADER_STORAGE_BUFFER, bytes, nullptr, access | GL_CLIENT_STORAGE_BIT);
        // A buffer the driver will not map (null) is read with glGetBufferSubData, like unmapped ones; the
        // error the failed map raised is taken here, so that readback's error check does not report it.
        pointer = static_cast<const float*>(gl.MapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, bytes, access));
        if (!pointer) gl.GetError();
        return b;
      };
      for (int set = 0; set < 2; ++set) {
        p.out_position[set] = out(12, p.mapped_position[set]);
        p.out_normal[set] = out(p.normals ? 12 : 0, p.mapped_normal[set]);
        p.out_tangent[set] = out(p.tangents ? 16 : 0, p.mapped_tangent[set]);
      }
    }
  }

  GLuint program(const Variant& v) {
    const auto it = programs.find(v);
    if (it != programs.end()) return it->second;
    const GLuint p = compile_program(gl, v);
    programs.emplace(v, p);
    return p;
  }

  void upload_texture(size_t instance, const BoneTexture& tex) {
    GLuint& t = textures[instance];
    if (t) gl.DeleteTextures(1, &t);
    gl.GenTextures(1, &t);
    gl.BindTexture(GL_TEXTURE_2D, t);
    gl.TexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, GLsizei(tex.width()), GLsizei(tex.frames));
    gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, GLsizei(tex.width()), GLsizei(tex.frames), GL_RGBA, GL_FLOAT,
                     tex.rgba.data());
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }

  void read_back(GLsync done, size_t first, size_t count, int set, bool copy, KernelTimes& times, DeformedBatch& out) {
    out.first_frame = first;
    out.frame_count = count;
    // Waiting for the fence is the GPU's deformation time not hidden behind our own work; what follows
    // is the copy back.
    const Clock::time_point wait = Clock::now();
    gl.ClientWaitSync(done, GL_SYNC_FLUSH_COMMANDS_BIT, GLuint64(-1));
    gl.DeleteSync(done);
    times.deform += since(wait);
    const Clock::time_point start = Clock::now();
    out.primitives.resize(prims.size());
    for (size_t i = 0; i < prims.size(); ++i) {
      const Prim& p = prims[i];
      DeformedBatch::Primitive& r = out.primitives[i];
      r.vertices = p.vertices;
      auto read = [&](GLuint b, const float* mapped_data, std::vector<float>& dst, size_t per_vertex) {
        dst.resize(copy ? p.vertices * per_vertex * count : 0);
        if (dst.empty()) return;
        if (mapped_data) {
          std::memcpy(dst.data(), mapped_data, dst.size() * 4);
          return;
        }
        gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, b);
        gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(dst.size() * 4), dst.data());
      };
      read(p.out_position[set], p.mapped_position[set], r.positions, 3);
      read(p.out_normal[set], p.mapped_normal[set], r.normals, p.normals ? 3 : 0);
      read(p.out_tangent[set], p.mapped_tangent[set], r.tangents, p.tangents ? 4 : 0);
    }
    if (const GLenum e = gl.GetError(); e != GL_NO_ERROR)
      throw std::runtime_error("OpenGL error " + std::to_string(e) + " during GPU deformation");
    times.readback += since(start);
  }

  // Uploads the bone textures and morph weights of one batch and dispatches every primitive into `set`.
  GLsync dispatch(std::span<const BoneTexture> bones, std::span<const Pose> poses, int set, KernelTimes& times) {
    const size_t count = poses.size();
    const Clock::time_point submit = Clock::now();
    for (size_t i = 0; i < instances.size(); ++i) {
      if (bones[i].width() > size_t(max_texture_width))
        throw InputError("skin of node " + std::to_string(instances[i].node) + " needs a bone texture " +
                         std::to_string(bones[i].width()) + " texels wide; this GPU allows " +
                         std::to_string(max_texture_width));
      upload_texture(i, bones[i]);  // the previous batch's texture lives on until its dispatch is done
    }
    for (Prim& p : prims) {
      const BoneTexture& tex = bones[p.instance];
      if (p.targets) {
        std::vector<float> w(count * size_t(p.targets), 0.0f);
        for (size_t f = 0; f < count; ++f) {
          const std::vector<double>& morph = poses[f].weights[size_t(instances[p.instance].node)];
          for (size_t m = 0; m < size_t(p.targets) && m < morph.size(); ++m) w[f * size_t(p.targets) + m] = float(morph[m]);
        }
        gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, p.morph_weight);  // new storage: the last batch keeps its own
        gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(w.size() * 4), w.data(), GL_STREAM_DRAW);
      }
      const GLuint prog = program({mode, tex.texels_per_joint, p.influences, p.targets, p.normals, p.tangents});
      gl.UseProgram(prog);
      const GLuint buffers[] = {p.rest_position, p.rest_normal, p.rest_tangent, p.influence, p.morph_offset,
                                p.morph_weight, p.out_position[set], p.out_normal[set], p.out_tangent[set]};
      for (GLuint b = 0; b < 9; ++b) gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, b, buffers[b]);
      gl.ActiveTexture(GL_TEXTURE0);
      gl.BindTexture(GL_TEXTURE_2D, textures[p.instance]);
      gl.Uniform1i(gl.GetUniformLocation(prog, "bones"), 0);
      gl.Uniform1ui(gl.GetUniformLocation(prog, "vertex_count"), GLuint(p.vertices));
      gl.Uniform1i(gl.GetUniformLocation(prog, "first_row"), 0);
      gl.DispatchCompute(GLuint((p.vertices + 63) / 64), GLuint(count), 1);
    }
    // Mapped outputs: the shader's writes must reach the client's mapping before the fence signals.
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | (mapped ? GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT : 0));
    const GLsync fence = gl.FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    gl.Flush();  // start it now: the previous batch is read back while this one runs
    times.deform += since(submit);
    return fence;
  }

};

SkinKernel::SkinKernel(GpuContext& context, const Asset& asset, std::vector<MeshInstance> instances, BlendMode mode,
                       size_t memory_budget, bool mapped_readback)
    : impl_(std::make_unique<Impl>(context, asset, std::move(instances), mode, memory_budget, mapped_readback)) {}
SkinKernel::~SkinKernel() = default;
size_t SkinKernel::frames_per_batch() const { return impl_->batch; }
bool SkinKernel::mapped_readback() const { return impl_->mapped; }

void SkinKernel::make_current() { impl_->context.make_current(); }

SkinKernel::Submitted SkinKernel::dispatch(std::span<const BoneTexture> bones, std::span<const Pose> poses, int set,
                                           KernelTimes& times) {
  return {impl_->dispatch(bones, poses, set, times), poses.size(), set};
}

void SkinKernel::read_back(const Submitted& batch, size_t first_frame, bool copy, KernelTimes& times, DeformedBatch& out) {
  impl_->read_back(static_cast<GLsync>(batch.fence), first_frame, batch.frames, batch.set, copy, times, out);
}

}  // namespace dqskin::gpu
