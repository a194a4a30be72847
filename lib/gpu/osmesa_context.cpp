// OSMesa backend: Mesa's off-screen rasterizer with a core-profile context. Kept in its own file and
// optional at build time (DQSKIN_HAVE_OSMESA), since Mesa removed libOSMesa after 24.x.
#include "gl_info.hpp"
#include "gpu_backends.hpp"

#include <GL/osmesa.h>

#include <vector>

namespace dqskin::gpu {
namespace {

class OsMesaContext final : public GpuContext {
public:
  explicit OsMesaContext(OSMesaContext context) : context_(context), pixels_(4 * 4 * 4) { info_.backend = "osmesa"; }
  ~OsMesaContext() override { OSMesaDestroyContext(context_); }
  void make_current() override {
    // OSMesa needs a colour buffer even when nothing is drawn into it; a 4×4 one.
    OSMesaMakeCurrent(context_, pixels_.data(), GL_UNSIGNED_BYTE, 4, 4);
  }
  void* proc_address(const char* name) const override {
    return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
  }
  GpuContextInfo& mutable_info() { return info_; }

private:
  OSMesaContext context_;
  std::vector<unsigned char> pixels_;
};

void* osmesa_loader(const char* name, const void*) { return reinterpret_cast<void*>(OSMesaGetProcAddress(name)); }

}  // namespace

std::unique_ptr<GpuContext> create_osmesa_context(std::string& report) {
  const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                            OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 4,
                            OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
  OSMesaContext raw = OSMesaCreateContextAttribs(attributes, nullptr);
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
