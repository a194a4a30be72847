// The fast CPU deformer behind the Deformer interface (internal to lib/deform): float, vectorized
// (fast_kernel.hpp), on every core. The deformer of --backend auto where no hardware GPU is present.
#pragma once

#include "dqskin/deformer.hpp"
#include "fast_kernel.hpp"

namespace dqskin::deform {

// The kernel build is best_kernel_isa() unless a test asks for another (which must run here). Throws
// InputError for a mode without a GPU path (dib) and for a joint index outside its skin.
std::unique_ptr<Deformer> make_fast_cpu_deformer(const Asset& asset, std::vector<MeshInstance> instances,
                                                 const DeformerOptions& options, KernelIsa isa = best_kernel_isa());

}  // namespace dqskin::deform
