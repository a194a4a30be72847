// Headless OpenGL contexts (docs/DESIGN.md §1.4: the GPU context (EGL or OSMesa) is a resource that deform
// and render borrow; nothing above them knows which backend runs). No EGL, OSMesa or GL type appears here.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

namespace dqskin {

// --backend, the one backend enum. egl and osmesa deform on that headless OpenGL context; fast-cpu on the
// vectorized float CPU deformer; cpu on the double-precision CPU reference; auto on a hardware GPU when
// EGL's device platform offers one, else on fast-cpu (deform_path in deformer.hpp decides). Render draws
// on a headless context whichever deformed: the one --backend names, else EGL, then OSMesa.
enum class Backend { kAuto, kEgl, kOsMesa, kFastCpu, kCpu };
const char* to_string(Backend backend);
bool parse_backend(const std::string& text, Backend& backend);
// The one-line refusal of a --backend value that parse_backend does not know.
std::string unknown_backend(const std::string& text);

// What was created, for --verbose and bake manifests.
struct GpuContextInfo {
  std::string backend;   // "egl-device", "egl-surfaceless" or "osmesa"
  std::string version;   // GL_VERSION
  std::string renderer;  // GL_RENDERER
  bool hardware = false; // a GPU, not a software rasterizer (llvmpipe, softpipe, SwiftShader)
};

// An OpenGL 4.3 core context, current on the creating thread, needing no display. Not copyable; the
// context is destroyed with the object.
class GpuContext {
public:
  virtual ~GpuContext() = default;
  GpuContext(const GpuContext&) = delete;
  GpuContext& operator=(const GpuContext&) = delete;

  virtual void make_current() = 0;
  // The backend's own get-proc-address (eglGetProcAddress, OSMesaGetProcAddress).
  virtual void* proc_address(const char* name) const = 0;
  const GpuContextInfo& info() const { return info_; }

protected:
  GpuContext() = default;
  GpuContextInfo info_;
};

// Thrown when no backend offers an OpenGL 4.3 core context; the message says which backends were tried
// and what each offered (exit status 3 in the CLI).
class NoGpuContext : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// kAuto tries EGL (the device platform, hardware devices first, then Mesa's surfaceless platform), then
// OSMesa when it was built in. kFastCpu and kCpu ask for a context as kAuto does: with a CPU deformer,
// render still draws on whichever context there is.
std::unique_ptr<GpuContext> create_gpu_context(Backend backend);
// A context on a hardware GPU of EGL's device platform, or null when there is none (auto's question).
std::unique_ptr<GpuContext> create_hardware_gpu_context();

}  // namespace dqskin
