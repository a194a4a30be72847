#include "render_manifest.hpp"

#include "../base/parallel_for.hpp"
#include "../job/job_manifest.hpp"
#include "../base/sha256.hpp"
#include "dqskin/version.hpp"

#include <filesystem>
#include <thread>

namespace dqskin::render_detail {
namespace {

using nlohmann::json;

const char* shade_name(Shade shade) {
  switch (shade) {
    case Shade::kLit: return "lit";
    case Shade::kNormals: return "normals";
    case Shade::kWeights: return "weights";
    case Shade::kModeDiff: return "mode-diff";
  }
  return "lit";
}

// Every flag that changes an image, so that shards run with other flags cannot be merged.
json settings(const RenderOptions& o) {
  const RendererOptions& r = o.renderer;
  json s = {{"width", r.width},
            {"height", r.height},
            {"samples", r.samples},
            {"background", {r.background.r, r.background.g, r.background.b, r.background.a}},
            {"shade", shade_name(r.shade)},
            {"format", extension(o.format)},
            {"sheet", o.sheet},
            {"gif", o.gif}};
  if (o.sheet) s["sheet_cell"] = o.sheet_cell;
  if (r.shade == Shade::kWeights) s["joint"] = o.joint;
  if (!o.camera_node.empty()) {
    s["camera"] = {{"node", o.camera_node}, {"size_from_camera", o.size_from_camera}};
  } else {
    json camera = {{"yaw", o.camera.yaw}, {"pitch", o.camera.pitch}, {"fov", o.camera.fov}, {"ortho", o.camera.ortho}};
    if (o.camera.distance) camera["distance"] = *o.camera.distance;
    s["camera"] = std::move(camera);
  }
  return s;
}

}  // namespace

std::string write_render_manifest(const std::vector<InputPlan>& plans, const RenderOptions& options,
                                  const RenderReport& report) {
  json inputs = json::array();
  for (size_t i = 0; i < plans.size(); ++i) {
    json in = job_manifest::input_record(plans[i], report.inputs[i].error);
    for (json& clip : in["animations"])
      for (const ModeDiffScale& m : report.mode_diff)
        if (m.input == plans[i].path && m.clip == clip["name"]) clip["mode_diff_max_distance"] = m.max_distance;
    inputs.push_back(std::move(in));
  }
  // The images were written by OpenImageIO from memory we do not keep: hashed from the files, on every core.
  std::vector<json> outputs(report.outputs.size());
  concurrency::parallel_for(outputs.size(), std::max(1u, std::thread::hardware_concurrency()), [&](size_t k) {
    const std::string path = options.out_dir + "/" + report.outputs[k];
    outputs[k] = {{"path", report.outputs[k]},
                  {"size", uint64_t(std::filesystem::file_size(path))},
                  {"sha256", sha256_file(path)}};
  });
  json manifest = {
      {"tool", {{"name", "dqskin"}, {"version", kVersion}}},
      {"backend", {{"name", report.gpu.backend}, {"renderer", report.gpu.renderer}, {"gl_version", report.gpu.version}}},
      {"deformer", report.deformer},
      {"mode", to_string(options.mode)},
      {"render", settings(options)},
      {"shard", {{"index", options.shard.index}, {"count", options.shard.count}}},
      {"inputs", std::move(inputs)},
      {"outputs", std::move(outputs)},
  };
  // --max-influences only where given: the manifests of other runs stay as they were.
  if (options.load.max_influences > 0) manifest["max_influences"] = options.load.max_influences;
  return job_manifest::write(options.out_dir, job_manifest::file_name("render-manifest", options.shard), manifest);
}

}  // namespace dqskin::render_detail
