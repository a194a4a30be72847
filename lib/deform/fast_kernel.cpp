// Which build of the fast CPU kernel runs: the widest one this CPU has, chosen once.
#include "fast_kernel.hpp"

namespace dqskin::deform {

namespace baseline {
KernelFunction kernel_function(KernelMode mode);
}
#if DQSKIN_KERNEL_AVX2
namespace avx2_fma {
KernelFunction kernel_function(KernelMode mode);
}
#endif

const char* to_string(KernelIsa isa) { return isa == KernelIsa::kAvx2Fma ? "avx2-fma" : "baseline"; }

bool runs_here(KernelIsa isa) {
  if (isa == KernelIsa::kBaseline) return true;
#if DQSKIN_KERNEL_AVX2
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
  return false;
#endif
}

KernelIsa best_kernel_isa() {
  static const KernelIsa best = runs_here(KernelIsa::kAvx2Fma) ? KernelIsa::kAvx2Fma : KernelIsa::kBaseline;
  return best;
}

KernelFunction kernel_function(KernelMode mode, KernelIsa isa) {
#if DQSKIN_KERNEL_AVX2
  if (isa == KernelIsa::kAvx2Fma) return avx2_fma::kernel_function(mode);
#endif
  (void)isa;
  return baseline::kernel_function(mode);
}

}  // namespace dqskin::deform
