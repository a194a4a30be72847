// The fast CPU kernel for x86-64 with AVX2 and FMA (lib/CMakeLists.txt compiles this file alone with
// -march=x86-64-v3); fast_kernel.cpp calls it only where the CPU says it has both.
#define DQSKIN_KERNEL_NAMESPACE avx2_fma
#include "fast_kernel_body.hpp"
