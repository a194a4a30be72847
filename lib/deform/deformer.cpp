// Which deformer runs, decided once: the rule that dib has only the CPU reference, and the factory.
#include "dqskin/deformer.hpp"

#include "dqskin/gpu_deform.hpp"
#include "reference_deformer.hpp"

#include <stdexcept>

namespace dqskin {

bool has_gpu_path(BlendMode mode) { return mode != BlendMode::kDib; }

bool deforms_on_cpu(Backend backend, BlendMode mode) { return backend == Backend::kCpu || !has_gpu_path(mode); }

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
