// Which deformer runs, decided once: the rule that dib has only the CPU reference, auto's choice between a
// hardware GPU and the fast CPU deformer, and the factory.
#include "dqskin/deformer.hpp"

#include "dqskin/gpu_deform.hpp"
#include "fast_cpu_deformer.hpp"
#include "fast_kernel.hpp"
#include "reference_deformer.hpp"

#include <stdexcept>

namespace dqskin {

bool has_gpu_path(BlendMode mode) { return mode != BlendMode::kDib; }

DeformPath deform_path(Backend backend, BlendMode mode, const GpuContext* context) {
  if (backend == Backend::kCpu || !has_gpu_path(mode)) return DeformPath::kReference;
  if (backend == Backend::kFastCpu) return DeformPath::kFastCpu;
  if (backend == Backend::kAuto) return context && context->info().hardware ? DeformPath::kGpu : DeformPath::kFastCpu;
  return DeformPath::kGpu;
}

std::string describe(DeformPath path) {
  switch (path) {
    case DeformPath::kGpu: return "gpu";
    case DeformPath::kFastCpu: return std::string("fast-cpu (") + deform::to_string(deform::best_kernel_isa()) + ")";
    case DeformPath::kReference: break;
  }
  return "cpu-reference";
}

GpuContextInfo cpu_deformer_info(DeformPath path) {
  if (path == DeformPath::kFastCpu)
    return {"fast-cpu", "", std::string("dqskin fast CPU deformer (float, ") + deform::to_string(deform::best_kernel_isa()) + ")"};
  return {"cpu", "", "dqskin CPU reference (double precision)"};
}

std::unique_ptr<Deformer> make_deformer(GpuContext* context, const Asset& asset, std::vector<MeshInstance> instances,
                                        const DeformerOptions& options) {
  switch (deform_path(options.backend, options.mode, context)) {
    case DeformPath::kReference: return deform::make_reference_deformer(asset, std::move(instances), options);
    case DeformPath::kFastCpu: return deform::make_fast_cpu_deformer(asset, std::move(instances), options);
    case DeformPath::kGpu: break;
  }
  if (!context) throw std::invalid_argument("make_deformer: the GPU path needs a GL context");
  GpuDeformOptions gpu;
  gpu.mode = options.mode;
  gpu.memory_budget = options.gpu_memory;
  return std::make_unique<GpuDeformer>(*context, asset, std::move(instances), gpu);
}

}  // namespace dqskin
