// The backends behind create_gpu_context, one file each (internal). Each returns a current 4.3 core
// context, or null after appending "backend: what it offered; " to `report`.
#pragma once

#include "dqskin/gpu_context.hpp"

#include <memory>
#include <string>

namespace dqskin::gpu {

// `hardware_only`: hardware devices of the device platform only, and no software renderer behind them.
std::unique_ptr<GpuContext> create_egl_context(std::string& report, bool hardware_only);
#ifdef DQSKIN_HAVE_OSMESA
std::unique_ptr<GpuContext> create_osmesa_context(std::string& report);
#endif

}  // namespace dqskin::gpu
