// The fast CPU kernel for the target's baseline instruction set (SSE2 on x86-64).
#define DQSKIN_KERNEL_NAMESPACE baseline
#include "fast_kernel_body.hpp"
