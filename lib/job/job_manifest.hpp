// What every job's manifest shares (bake's manifest.json, render's render-manifest.json): the file names,
// shards included, the record of each input and its animations, and the text as written. One writer for
// all of them, so that a manifest merged from shards (dqskin merge) is byte-identical to an unsharded one.
#pragma once

#include "dqskin/job.hpp"
#include "job_plan.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>

namespace dqskin::job_manifest {

// "BASE.json" for a whole job, "BASE.shard-I-of-N.json" for one shard of it, so that shards sharing a
// folder do not collide.
std::string file_name(std::string_view base, const Shard& shard);

// An input as planned: path, size and SHA-256 of the file, its output folder, its error (when it failed),
// scene, and per animation its name, folder, frame times and numbers. Every shard plans the same, so the
// records of all shards of a job are equal.
nlohmann::json input_record(const InputPlan& plan, const std::string& error);

// The manifest's bytes: indented, keys sorted, invalid UTF-8 (input paths may be any bytes) replaced.
std::string text(const nlohmann::json& manifest);

// Writes `manifest` as `folder`/`name`, whole or not at all, replacing an earlier one (the record of the
// latest job), and returns its path. Then deletes what a killed run of the same job left beside the files
// it lists and beside the manifest itself (leftover_files.hpp): they are all in place now.
std::string write(const std::string& folder, const std::string& name, const nlohmann::json& manifest);

// Deletes what a killed run of the job left beside the manifest `name` in `folder` and beside every file
// `manifest` lists: what write() does once the manifest is in place. Never throws (a leftover that stays
// is reported by dqskin verify).
void clear_leftovers(const std::string& folder, const std::string& name, const nlohmann::json& manifest) noexcept;

}  // namespace dqskin::job_manifest
