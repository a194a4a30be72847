// The fast CPU deformer's inner loop (internal to lib/deform): glsl/skin.comp's arithmetic in float over
// blocks of kLanes vertices in structure-of-arrays layout, so that one vector instruction serves kLanes
// vertices. Only plain pointers cross this header: the kernel is compiled once per instruction set
// (fast_kernel_body.hpp) and must not share inline library code with the rest of the program.
#pragma once

#include <cstddef>
#include <cstdint>

namespace dqskin::deform {

// Vertices per block: eight floats fill one AVX2 register (two SSE2 registers).
constexpr size_t kLanes = 8;

// Floats per joint in a frame's palette, one cache line. lbs: the 3×4 joint matrix by columns (a00 a10 a20,
// a01 …, then the translation). dqs: the rigid part's real (x y z w) and dual (x y z w) quaternions, then the
// symmetric scale S (xx xy xz yy yz zz) of the two-phase rule.
constexpr size_t kPaletteStride = 16;

// One primitive's rest data, every array padded to blocks · kLanes entries.
struct KernelPrimitive {
  size_t blocks = 0;
  size_t influences = 0;                   // K, per vertex
  const float* position[3] = {};           // x, y, z
  const float* normal[3] = {};             // null when the primitive has none
  const float* tangent[4] = {};            // x, y, z, w; null when none
  const int32_t* joint = nullptr;          // [k][vertex]; k = 0 is the largest weight (the dqs pivot)
  const float* weight = nullptr;           // [k][vertex], divided by their sum; 0 pads
  size_t targets = 0;
  // Per target, position, normal and tangent offsets, 3 arrays each ([target · 3 + part][c][vertex]); null
  // where the target lacks that attribute.
  const float* const* morph = nullptr;
};

// One frame: the palette (joints · kPaletteStride floats) and morph weights in, AoS floats out.
struct KernelFrame {
  const float* palette = nullptr;
  const float* morph_weights = nullptr;  // one per target
  size_t vertices = 0;                   // the unpadded count: outputs have exactly this many
  float* positions = nullptr;            // 3 per vertex
  float* normals = nullptr;              // 3 per vertex, when the primitive has normals
  float* tangents = nullptr;             // 4 per vertex, when it has tangents
};

enum class KernelMode { kLbs, kDqs, kDqsScale };

// Deforms blocks [first, last) of `prim` for `frame`.
using KernelFunction = void (*)(const KernelPrimitive& prim, const KernelFrame& frame, size_t first, size_t last);

// The builds of the kernel: the target's baseline (SSE2 on x86-64), and on x86-64 also AVX2 with FMA.
enum class KernelIsa { kBaseline, kAvx2Fma };
const char* to_string(KernelIsa isa);
// Whether this program has a build for `isa` and this CPU runs it.
bool runs_here(KernelIsa isa);
// The widest build this CPU runs; the same answer for the life of the process, so a machine's results
// are identical run after run.
KernelIsa best_kernel_isa();
// The kernel for `mode` in the build `isa` (which must run here).
KernelFunction kernel_function(KernelMode mode, KernelIsa isa);

}  // namespace dqskin::deform
