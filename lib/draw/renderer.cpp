// The rasterizer of `dqskin render`: glsl/render.vert and glsl/render.frag drawing deformed frames into an
// offscreen MSAA framebuffer of the borrowed headless context, resolved and read back as linear floats.
#include "dqskin/renderer.hpp"
#include "dqskin/triangles.hpp"

#include "dqskin/error.hpp"
#include "../gpu/gl_functions.hpp"
#include "../gpu/shader_program.hpp"
#include "texture_image.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cassert>
#include <cstring>
#include <map>
#include <stdexcept>

namespace dqskin {
namespace {

using gpu::Gl;

GLuint link_program(const Gl& gl, const std::string& defines) {
  return gpu::build_program(gl, {{GL_VERTEX_SHADER, gpu::kRenderVert}, {GL_FRAGMENT_SHADER, gpu::kRenderFrag}}, defines);
}

// Vertex attribute locations of glsl/render.vert.
constexpr GLuint kPositionLocation = 0, kNormalLocation = 1, kScalarLocation = 2, kUvLocation = 3, kColorLocation = 4;

const char* shade_define(Shade shade) {
  switch (shade) {
    case Shade::kNormals: return "#define SHADE_NORMALS\n";
    case Shade::kWeights:
    case Shade::kModeDiff: return "#define SHADE_WEIGHTS\n";  // both a scalar as a heat map
    case Shade::kLit: break;
  }
  return "#define SHADE_LIT\n";
}

}  // namespace

struct Renderer::Impl {
  struct Prim {
    size_t vertices = 0;
    GLsizei index_count = 0;  // 0: not drawn (points, lines, or no triangles)
    glm::vec4 base_color{1.0f};
    GLuint texture = 0;       // the base color texture (owned by `textures`), or 0
    glm::mat3 uv_transform{1.0f};  // its KHR_texture_transform
    AlphaMode alpha_mode = AlphaMode::kOpaque;
    float alpha_cutoff = 0.5f;
    GLuint vao = 0, indices = 0, positions = 0, normals = 0, scalars = 0, uvs = 0, colors = 0;
  };

  GpuContext& context;
  Gl gl;
  RendererOptions options;
  std::vector<Prim> prims;
  std::map<int, GLuint> textures;  // per glTF texture used by a drawn primitive
  GLuint program = 0;
  GLuint msaa_fbo = 0, resolve_fbo = 0;
  GLuint msaa_color = 0, msaa_depth = 0, resolve_color = 0;

  Impl(GpuContext& c, const Asset& asset, const std::vector<MeshInstance>& instances, const RendererOptions& o)
      : context(c), options(o) {
    context.make_current();
    if (const std::string missing = gl.load(context); !missing.empty())
      throw NoGpuContext("the OpenGL context has no " + missing);
    try {
      make_framebuffers();
      program = link_program(gl, shade_define(options.shade));
      upload(asset, instances);
    } catch (...) {
      release();
      throw;
    }
  }

  ~Impl() { release(); }

  void release() {
    context.make_current();
    for (Prim& p : prims) {
      const GLuint b[] = {p.indices, p.positions, p.normals, p.scalars, p.uvs, p.colors};
      gl.DeleteBuffers(GLsizei(std::size(b)), b);
      gl.DeleteVertexArrays(1, &p.vao);
    }
    prims.clear();
    for (const auto& [index, texture] : textures) gl.DeleteTextures(1, &texture);
    textures.clear();
    if (program) gl.DeleteProgram(program);
    const GLuint fbos[] = {msaa_fbo, resolve_fbo};
    gl.DeleteFramebuffers(2, fbos);
    const GLuint rbs[] = {msaa_color, msaa_depth, resolve_color};
    gl.DeleteRenderbuffers(3, rbs);
    program = msaa_fbo = resolve_fbo = msaa_color = msaa_depth = resolve_color = 0;
  }

  void make_framebuffers() {
    GLint max_size = 0, max_samples = 0;
    gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
    gl.GetIntegerv(GL_MAX_SAMPLES, &max_samples);
    if (options.width < 1 || options.height < 1 || options.width > max_size || options.height > max_size)
      throw InputError("image size " + std::to_string(options.width) + "x" + std::to_string(options.height) +
                       " is outside 1 to " + std::to_string(max_size) + " pixels a side on this GPU");
    if (options.samples < 1 || options.samples > max_samples)
      throw InputError("--samples " + std::to_string(options.samples) + " is outside 1 to " + std::to_string(max_samples) +
                       " on this GPU");
    auto renderbuffer = [&](GLsizei samples, GLenum format) {
      GLuint rb = 0;
      gl.GenRenderbuffers(1, &rb);
      gl.BindRenderbuffer(GL_RENDERBUFFER, rb);
      gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, options.width, options.height);
      return rb;
    };
    // RGBA16F: linear values with enough precision for EXR output and for sRGB encoding without banding.
    const GLsizei samples = options.samples == 1 ? 0 : options.samples;
    msaa_color = renderbuffer(samples, GL_RGBA16F);
    msaa_depth = renderbuffer(samples, GL_DEPTH_COMPONENT24);
    resolve_color = renderbuffer(0, GL_RGBA16F);
    gl.GenFramebuffers(1, &msaa_fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, msaa_fbo);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaa_color);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msaa_depth);
    check_framebuffer("multisampled");
    gl.GenFramebuffers(1, &resolve_fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, resolve_fbo);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolve_color);
    check_framebuffer("resolve");
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  }

  void check_framebuffer(const char* which) const {
    const GLenum status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error(std::string("the ") + which + " framebuffer is incomplete (status " +
                               std::to_string(status) + ")");
  }

  void upload(const Asset& asset, const std::vector<MeshInstance>& instances) {
    std::map<int, Image8> decoded;  // per glTF image, decoded once however many textures use it
    for (const MeshInstance& inst : instances) {
      for (const Primitive& src : asset.meshes[size_t(inst.mesh)].primitives) {
        Prim p;
        p.vertices = src.vertex_count();
        const bool triangles = src.mode == PrimitiveMode::kTriangles || src.mode == PrimitiveMode::kTriangleStrip ||
                               src.mode == PrimitiveMode::kTriangleFan;
        gl.GenVertexArrays(1, &p.vao);
        gl.BindVertexArray(p.vao);
        if (triangles) {
          const std::vector<uint32_t> list = triangle_list(src);
          p.index_count = GLsizei(list.size());
          gl.GenBuffers(1, &p.indices);
          gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, p.indices);  // recorded in the VAO
          gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(std::max<size_t>(4, list.size() * 4)),
                        list.empty() ? nullptr : list.data(), GL_STATIC_DRAW);
        }
        GLuint* buffers[] = {&p.positions, &p.normals, &p.scalars, &p.uvs, &p.colors};
        for (GLuint* b : buffers) gl.GenBuffers(1, b);
        prims.push_back(p);  // owned by release() from here on, even if the material below throws
        if (triangles && src.material >= 0) use_material(asset, src, prims.back(), decoded);
        // Attributes that do not change from frame to frame are set once, in the VAO.
        std::span<const float> colors;
        if (!src.colors.empty()) colors = {&src.colors[0].x, src.colors.size() * 4};
        attribute(p.colors, kColorLocation, 4, colors);
        gl.BindVertexArray(0);
      }
    }
  }

  // The primitive's material: base color factor, alpha mode, and the base color texture with the UV set
  // it reads (drawn without the texture when the primitive lacks that set, which glTF-Validator reports).
  void use_material(const Asset& asset, const Primitive& src, Prim& p, std::map<int, Image8>& decoded) {
    const Material& material = asset.materials[size_t(src.material)];
    p.base_color = material.base_color;
    p.alpha_cutoff = material.alpha_cutoff;
    p.alpha_mode = options.shade == Shade::kLit ? material.alpha_mode : AlphaMode::kOpaque;
    const TextureRef& ref = material.base_color_texture;
    if (options.shade != Shade::kLit) return;  // only lit shows the material; the others show geometry
    const std::vector<glm::vec2>* uv = ref.texcoord == 0 ? &src.uv0 : ref.texcoord == 1 ? &src.uv1 : nullptr;
    if (ref.texture < 0 || !uv || uv->empty()) return;
    const Texture& texture = asset.textures[size_t(ref.texture)];
    if (texture.image < 0) return;  // only an extension's image (KTX2): the factor alone, as without a texture
    attribute(p.uvs, kUvLocation, 2, {&(*uv)[0].x, uv->size() * 2});
    p.uv_transform = ref.transform.matrix();
    if (const auto found = textures.find(ref.texture); found != textures.end()) {
      p.texture = found->second;
      return;
    }
    auto image = decoded.find(texture.image);
    if (image == decoded.end()) {
      GLint max_side = 0;
      gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
      image = decoded.emplace(texture.image, decode_texture_image(asset.images[size_t(texture.image)],
                                                                  size_t(texture.image), max_side)).first;
    }
    p.texture = textures[ref.texture] = make_texture(image->second, texture.sampler);
  }

  // An sRGB texture with a full mipmap chain (filtered in linear light by the GL), sampled as `sampler`
  // says; filters the file leaves open are trilinear.
  GLuint make_texture(const Image8& image, const Sampler& sampler) {
    GLuint texture = 0;
    gl.GenTextures(1, &texture);
    gl.BindTexture(GL_TEXTURE_2D, texture);
    int levels = 1;
    while ((std::max(image.width, image.height) >> levels) > 0) ++levels;
    gl.TexStorage2D(GL_TEXTURE_2D, levels, GL_SRGB8_ALPHA8, image.width, image.height);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);  // the GL default, for whoever uploads next
    gl.GenerateMipmap(GL_TEXTURE_2D);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, sampler.min_filter ? sampler.min_filter : GL_LINEAR_MIPMAP_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, sampler.mag_filter ? sampler.mag_filter : GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, sampler.wrap_s);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, sampler.wrap_t);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    return texture;
  }

  // Points `location` of the bound VAO at `data` (components floats per vertex), or, when data is
  // empty, disables the array so that the attribute reads its constant (set in draw()).
  void attribute(GLuint buffer, GLuint location, GLint components, std::span<const float> data) {
    if (data.empty()) {
      gl.DisableVertexAttribArray(location);
      return;
    }
    gl.BindBuffer(GL_ARRAY_BUFFER, buffer);
    gl.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * 4), data.data(), GL_STREAM_DRAW);
    gl.VertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, 0, nullptr);
    gl.EnableVertexAttribArray(location);
  }

  Image render(const FrameView& frame, const Camera& camera, std::span<const std::vector<float>> scalars) {
    assert(frame.primitives.size() == prims.size());
    context.make_current();
    gl.BindFramebuffer(GL_FRAMEBUFFER, msaa_fbo);
    gl.Viewport(0, 0, options.width, options.height);
    gl.ClearBufferfv(GL_COLOR, 0, glm::value_ptr(options.background));
    const float far_depth = 1.0f;
    gl.ClearBufferfv(GL_DEPTH, 0, &far_depth);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.Enable(GL_MULTISAMPLE);

    gl.UseProgram(program);
    const glm::mat4 view_projection = camera.projection * camera.view;
    gl.UniformMatrix4fv(gl.GetUniformLocation(program, "view_projection"), 1, GL_FALSE, glm::value_ptr(view_projection));
    gl.Uniform3f(gl.GetUniformLocation(program, "eye"), camera.eye.x, camera.eye.y, camera.eye.z);
    // The key light comes from above, to the left of the camera: fixed to the view, so every model and
    // every yaw is lit the same way (world-fixed lights leave the back of a turned model dark).
    const glm::mat3 camera_to_world = glm::transpose(glm::mat3(camera.view));
    const glm::vec3 key = glm::normalize(camera_to_world * glm::vec3(-0.5f, 0.8f, 0.6f));
    gl.Uniform3f(gl.GetUniformLocation(program, "key_direction"), key.x, key.y, key.z);
    const GLint base_color = gl.GetUniformLocation(program, "base_color");
    const GLint has_normals = gl.GetUniformLocation(program, "has_normals");
    const GLint has_texture = gl.GetUniformLocation(program, "has_texture");
    const GLint alpha_mode = gl.GetUniformLocation(program, "alpha_mode");
    const GLint alpha_cutoff = gl.GetUniformLocation(program, "alpha_cutoff");
    const GLint uv_transform = gl.GetUniformLocation(program, "uv_transform");
    gl.Uniform1i(gl.GetUniformLocation(program, "base_color_texture"), 0);
    gl.ActiveTexture(GL_TEXTURE0);

    // Opaque and masked primitives first, then blended ones over them in file order (glTF leaves the
    // order of blended surfaces to the viewer; file order keeps images reproducible), testing depth
    // without writing it.
    for (const bool blended : {false, true}) {
      if (blended) {
        gl.Enable(GL_BLEND);
        gl.BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // the shader writes premultiplied color
        gl.DepthMask(GL_FALSE);
      }
      for (size_t i = 0; i < prims.size(); ++i) {
        const Prim& p = prims[i];
        const PrimitiveView& view = frame.primitives[i];
        if (p.index_count == 0 || (p.alpha_mode == AlphaMode::kBlend) != blended) continue;
        assert(view.vertices == p.vertices && view.positions.size() == p.vertices * 3);
        gl.BindVertexArray(p.vao);
        attribute(p.positions, kPositionLocation, 3, view.positions);
        attribute(p.normals, kNormalLocation, 3, view.normals);
        const std::span<const float> s = i < scalars.size() ? std::span<const float>(scalars[i]) : std::span<const float>();
        attribute(p.scalars, kScalarLocation, 1, s.size() == p.vertices ? s : std::span<const float>());
        // What an attribute without an array reads (context state, not the VAO's).
        gl.VertexAttrib3f(kNormalLocation, 0.0f, 0.0f, 1.0f);
        gl.VertexAttrib1f(kScalarLocation, 0.0f);
        gl.VertexAttrib2f(kUvLocation, 0.0f, 0.0f);
        gl.VertexAttrib4f(kColorLocation, 1.0f, 1.0f, 1.0f, 1.0f);
        gl.Uniform4f(base_color, p.base_color.r, p.base_color.g, p.base_color.b, p.base_color.a);
        gl.Uniform1i(has_normals, view.normals.empty() ? 0 : 1);
        gl.Uniform1i(has_texture, p.texture ? 1 : 0);
        gl.BindTexture(GL_TEXTURE_2D, p.texture);
        gl.UniformMatrix3fv(uv_transform, 1, GL_FALSE, glm::value_ptr(p.uv_transform));
        gl.Uniform1i(alpha_mode, int(p.alpha_mode));
        gl.Uniform1f(alpha_cutoff, p.alpha_cutoff);
        gl.DrawElements(GL_TRIANGLES, p.index_count, GL_UNSIGNED_INT, nullptr);
      }
    }
    gl.Disable(GL_BLEND);
    gl.DepthMask(GL_TRUE);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    gl.BindVertexArray(0);

    // Resolve the samples (a box filter over each pixel's samples) and read the result back.
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, msaa_fbo);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo);
    gl.BlitFramebuffer(0, 0, options.width, options.height, 0, 0, options.width, options.height, GL_COLOR_BUFFER_BIT,
                       GL_NEAREST);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    Image image;
    image.width = options.width;
    image.height = options.height;
    const size_t row = size_t(options.width) * 4;
    std::vector<float> bottom_up(row * size_t(options.height));
    gl.ReadPixels(0, 0, options.width, options.height, GL_RGBA, GL_FLOAT, bottom_up.data());
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.Disable(GL_DEPTH_TEST);
    if (const GLenum e = gl.GetError(); e != GL_NO_ERROR)
      throw std::runtime_error("OpenGL error " + std::to_string(e) + " while rendering");
    // GL's rows start at the bottom; image files start at the top.
    image.rgba.resize(bottom_up.size());
    for (size_t y = 0; y < size_t(options.height); ++y)
      std::memcpy(&image.rgba[y * row], &bottom_up[(size_t(options.height) - 1 - y) * row], row * sizeof(float));
    return image;
  }
};

Renderer::Renderer(GpuContext& context, const Asset& asset, std::vector<MeshInstance> instances,
                   const RendererOptions& options)
    : impl_(std::make_unique<Impl>(context, asset, instances, options)) {}
Renderer::~Renderer() = default;

Image Renderer::render(const FrameView& frame, const Camera& camera, std::span<const std::vector<float>> scalars) {
  return impl_->render(frame, camera, scalars);
}

bool parse_shade(const std::string& text, Shade& shade) {
  if (text == "lit") shade = Shade::kLit;
  else if (text == "normals") shade = Shade::kNormals;
  else if (text == "weights") shade = Shade::kWeights;
  else if (text == "mode-diff") shade = Shade::kModeDiff;
  else return false;
  return true;
}

}  // namespace dqskin
