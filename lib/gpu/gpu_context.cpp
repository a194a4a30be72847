// The backend factory: auto tries EGL, then OSMesa; auto's deformer asks for a hardware GPU alone.
#include "dqskin/gpu_context.hpp"

#include "gpu_backends.hpp"

namespace dqskin {

const char* to_string(Backend backend) {
  switch (backend) {
    case Backend::kAuto: return "auto";
    case Backend::kEgl: return "egl";
    case Backend::kOsMesa: return "osmesa";
    case Backend::kFastCpu: return "fast-cpu";
    case Backend::kCpu: return "cpu";
  }
  return "?";
}

bool parse_backend(const std::string& text, Backend& backend) {
  for (Backend b : {Backend::kAuto, Backend::kEgl, Backend::kOsMesa, Backend::kFastCpu, Backend::kCpu}) {
    if (text == to_string(b)) {
      backend = b;
      return true;
    }
  }
  return false;
}

std::string unknown_backend(const std::string& text) {
  return "--backend '" + text + "' is not one of auto, egl, osmesa, fast-cpu, cpu";
}

std::unique_ptr<GpuContext> create_gpu_context(Backend backend) {
  std::string report;
  const bool any = backend == Backend::kAuto || backend == Backend::kFastCpu || backend == Backend::kCpu;
  if (any || backend == Backend::kEgl)
    if (auto ctx = gpu::create_egl_context(report, false)) return ctx;
  if (any || backend == Backend::kOsMesa) {
#ifdef DQSKIN_HAVE_OSMESA
    if (auto ctx = gpu::create_osmesa_context(report)) return ctx;
#else
    report += "osmesa: not built in; ";
#endif
  }
  if (report.size() >= 2) report.resize(report.size() - 2);
  throw NoGpuContext("no OpenGL 4.3 core context: " + report);
}

std::unique_ptr<GpuContext> create_hardware_gpu_context() {
  std::string report;
  return gpu::create_egl_context(report, true);
}

}  // namespace dqskin
