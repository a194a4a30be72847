// OSMesa backend: Mesa's off-screen rasterizer with a core-profile context. Kept in its own file and
// optional at build time (DQSKIN_HAVE_OSMESA), since Mesa removed libOSMesa after 24.x.
//
// libOSMesa is opened when a context is first asked for, not linked: it brings LLVM, about 20 ms of
// every process's start, and only --backend osmesa (or EGL's failure) uses it.
#include "gl_info.hpp"
#include "gpu_backends.hpp"

#include <GL/osmesa.h>
#include <dlfcn.h>

#include <vector>

namespace dqskin::gpu {
namespace {

// The four entry points dqskin calls, from the library opened once (the soname it was built against).
struct OsMesaLibrary {
  decltype(&::OSMesaCreateContextAttribs) create = nullptr;
  decltype(&::OSMesaMakeCurrent) make_current = nullptr;
  decltype(&::OSMesaGetProcAddress) proc_address = nullptr;
  decltype(&::OSMesaDestroyContext) destroy = nullptr;
  std::string problem;  // why it cannot be used; empty when it can
};

template <class Function>
void find(void* library, const char* name, Function& function, std::string& problem) {
  function = reinterpret_cast<Function>(dlsym(library, name));
  if (!function && problem.empty()) problem = std::string("libOSMesa has no ") + name;
}

const OsMesaLibrary& osmesa() {
  static const OsMesaLibrary library = [] {
    OsMesaLibrary l;
    void* handle = dlopen(DQSKIN_OSMESA_SONAME, RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = dlerror();
      l.problem = std::string("cannot load ") + DQSKIN_OSMESA_SONAME + " (" + (why ? why : "no reason given") + ")";
      return l;
    }
    find(handle, "OSMesaCreateContextAttribs", l.create, l.problem);
    find(handle, "OSMesaMakeCurrent", l.make_current, l.problem);
    find(handle, "OSMesaGetProcAddress", l.proc_address, l.problem);
    find(handle, "OSMesaDestroyContext", l.destroy, l.problem);
    return l;
  }();
  return library;
}

class OsMesaContext final : public GpuContext {
public:
  explicit OsMesaContext(OSMesaContext context) : context_(context), pixels_(4 * 4 * 4) { info_.backend = "osmesa"; }
  ~OsMesaContext() override { osmesa().destroy(context_); }
  void make_current() override {
    // OSMesa needs a colour buffer even when nothing is drawn into it; a 4×4 one.
    osmesa().make_current(context_, pixels_.data(), GL_UNSIGNED_BYTE, 4, 4);
  }
  void* proc_address(const char* name) const override {
    return reinterpret_cast<void*>(osmesa().proc_address(name));
  }
  GpuContextInfo& mutable_info() { return info_; }

private:
  OSMesaContext context_;
  std::vector<unsigned char> pixels_;
};

void* osmesa_loader(const char* name, const void*) { return reinterpret_cast<void*>(osmesa().proc_address(name)); }

}  // namespace

std::unique_ptr<GpuContext> create_osmesa_context(std::string& report) {
  const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                            OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 4,
                            OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
  const OsMesaLibrary& library = osmesa();
  if (!library.problem.empty()) {
    report += "osmesa: " + library.problem + "; ";
    return nullptr;
  }
  OSMesaContext raw = library.create(attributes, nullptr);
  if (!raw) {
    report += "osmesa: no OpenGL 4.3 core context; ";
    return nullptr;
  }
  auto ctx = std::make_unique<OsMesaContext>(raw);
  ctx->make_current();
  const std::string why = query_gl(&osmesa_loader, nullptr, ctx->mutable_info());
  if (!why.empty()) {
    report += "osmesa: " + why + "; ";
    return nullptr;
  }
  return ctx;
}

}  // namespace dqskin::gpu
