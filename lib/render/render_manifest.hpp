// render-manifest.json (or render-manifest.shard-I-of-N.json): what a render drew from what, with which
// settings, and every image with its size and SHA-256, as bake's manifest.json records a bake, so that
// `dqskin verify` checks a render folder and `dqskin merge` joins a sharded render's manifests.
#pragma once

#include "../job/job_plan.hpp"
#include "dqskin/render.hpp"

#include <string>
#include <vector>

namespace dqskin::render_detail {

// Hashes report.outputs (on every core) and writes the manifest into options.out_dir; returns its path.
std::string write_render_manifest(const std::vector<InputPlan>& plans, const RenderOptions& options,
                                  const RenderReport& report);

}  // namespace dqskin::render_detail
