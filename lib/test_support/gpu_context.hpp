// A headless OpenGL context for a test that needs one (header-only, for the test executables).
#pragma once

#include "dqskin/gpu_context.hpp"

#include <memory>
#include <string>

namespace dqskin::testing_support {

// The context, or null when this machine offers none; the test then skips with GTEST_SKIP() (a macro, so
// it stays in the test body), naming the backend.
inline std::unique_ptr<GpuContext> context_or_null(Backend backend = Backend::kAuto) {
  try {
    return create_gpu_context(backend);
  } catch (const NoGpuContext&) {
    return nullptr;
  }
}

// The --backend that names `context`'s own backend: for a test of the GPU path on whatever context there is
// (auto would deform on the fast CPU deformer where the context is a software rasterizer).
inline Backend backend_of(const GpuContext& context) {
  return context.info().backend == "osmesa" ? Backend::kOsMesa : Backend::kEgl;
}

}  // namespace dqskin::testing_support
