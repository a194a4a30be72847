// The backend factory: auto tries EGL, then OSMesa.
#include "dqskin/gpu_context.hpp"

#include "gpu_backends.hpp"

namespace dqskin {

const char* to_string(GpuBackend backend) {
  switch (backend) {
    case GpuBackend::kAuto: return "auto";
    case GpuBackend::kEgl: return "egl";
    case GpuBackend::kOsMesa: return "osmesa";
  }
  return "?";
}

bool parse_gpu_backend(const std::string& text, GpuBackend& backend) {
  for (GpuBackend b : {GpuBackend::kAuto, GpuBackend::kEgl, GpuBackend::kOsMesa}) {
    if (text == to_string(b)) {
      backend = b;
      return true;
    }
  }
  return false;
}

std::unique_ptr<GpuContext> create_gpu_context(GpuBackend backend) {
  std::string report;
  if (backend == GpuBackend::kAuto || backend == GpuBackend::kEgl)
    if (auto ctx = gpu::create_egl_context(report)) return ctx;
  if (backend == GpuBackend::kAuto || backend == GpuBackend::kOsMesa) {
#ifdef DQSKIN_HAVE_OSMESA
    if (auto ctx = gpu::create_osmesa_context(report)) return ctx;
#else
    report += "osmesa: not built in; ";
#endif
  }
  if (report.size() >= 2) report.resize(report.size() - 2);
  throw NoGpuContext("no OpenGL 4.3 core context: " + report);
}

}  // namespace dqskin
