// A synthetic skinned character of any size, built in memory: for benchmarks that need 10k to 1M
// vertices without shipping such files.
#pragma once

#include "dqskin/asset.hpp"

#include <cstddef>

namespace dqskin::bench_detail {

// A cylinder of `vertices` vertices (radius 1, along +y) skinned to a chain of `joints` joints, 4
// influences per vertex, with one 2 s clip bending every joint about z (LINEAR, 9 keys). With
// `with_scale` every joint also scales non-uniformly, so its joint matrices are non-rigid (T = 5).
Asset make_synthetic_asset(size_t vertices, size_t joints, bool with_scale);

}  // namespace dqskin::bench_detail
