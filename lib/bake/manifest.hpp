// The bake manifest (docs/DESIGN.md §6.4): what was baked from what, and every
// output with its size and SHA-256. It holds no timings, so equal bakes write equal manifests.
#pragma once

#include "bake_plan.hpp"

namespace dqskin::bake_detail {

// Writes manifest.json (or manifest.shard-I-of-N.json) into options.out_dir; returns its path.
std::string write_manifest(const std::vector<InputPlan>& plans, const BakeOptions& options, const BakeReport& report);

}  // namespace dqskin::bake_detail
