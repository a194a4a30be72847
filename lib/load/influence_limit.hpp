// --max-influences (internal to the loader): the N largest influences of each vertex kept, the rest dropped.
#pragma once

#include "dqskin/asset.hpp"

namespace dqskin::gltf {

// For every primitive where some vertex has more than `max_influences` joints with weight: each of its
// vertices gets its influences merged per joint (two slots naming one joint add up), sorted by weight
// (descending; ties to the lower joint index, so the result does not depend on the slots' order), cut to
// the `max_influences` largest and renormalized to sum 1 in double, stored as float; a weight that
// rounds to 0 is dropped. That is what `dqskin lint --fix --max-influences N` writes for float weights,
// so a bake with the flag and a bake of the fixed file deform alike. Slots per vertex become the fewest
// multiple of 4 that holds the most kept (padding: joint 0, weight 0). Other primitives, and every one
// when `max_influences` < 1, are left as they are, byte for byte.
void keep_largest_influences(Asset& asset, int max_influences);

}  // namespace dqskin::gltf
