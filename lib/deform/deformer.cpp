// Which deformer runs, decided once: the backend names, the rule that dib has only the CPU reference,
// and the factory.
#include "dqskin/deformer.hpp"

#include "dqskin/gpu_deform.hpp"
#include "reference_deformer.hpp"

#include <stdexcept>

namespace dqskin {

const char* to_string(Backend backend) {
  switch (backend) {
    case Backend::kAuto: return "auto";
    case Backend::kEgl: return "egl";
    case Backend::kOsMesa: return "osmesa";
    case Backend::kCpu: return "cpu";
  }
  return "?";
}

bool parse_backend(const std::string& text, Backend& backend) {
  for (Backend b : {Backend::kAuto, Backend::kEgl, Backend::kOsMesa, Backend::kCpu}) {
    if (text == to_string(b)) {
      backend = b;
      return true;
    }
  }
  return false;
}

std::string unknown_backend(const std::string& text) {
  return "--backend '" + text + "' is not one of auto, egl, osmesa, cpu";
}

bool has_gpu_path(BlendMode mode) { return mode != BlendMode::kDib; }

bool deforms_on_cpu(Backend backend, BlendMode mode) { return backend == Backend::kCpu || !has_gpu_path(mode); }

GpuBackend context_backend(Backend backend) {
  switch (backend) {
    case Backend::kEgl: return GpuBackend::kEgl;
    case Backend::kOsMesa: return GpuBackend::kOsMesa;
    case Backend::kAuto:
    case Backend::kCpu: return GpuBackend::kAuto;
  }
  return GpuBackend::kAuto;
}

std::unique_ptr<Deformer> make_deformer(GpuContext* context, const Asset& asset, std::vector<MeshInstance> instances,
                                        const DeformerOptions& options) {
  if (deforms_on_cpu(options.backend, options.mode))
    return deform::make_reference_deformer(asset, std::move(instances), options);
  if (!context) throw std::invalid_argument("make_deformer: the GPU path needs a GL context");
  GpuDeformOptions gpu;
  gpu.mode = options.mode;
  gpu.memory_budget = options.gpu_memory;
  return std::make_unique<GpuDeformer>(*context, asset, std::move(instances), gpu);
}

}  // namespace dqskin
