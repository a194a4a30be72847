// The CPU reference behind the Deformer interface (internal to lib/deform).
#pragma once

#include "dqskin/deformer.hpp"

namespace dqskin::deform {

std::unique_ptr<Deformer> make_reference_deformer(const Asset& asset, std::vector<MeshInstance> instances,
                                                  const DeformerOptions& options);

}  // namespace dqskin::deform
