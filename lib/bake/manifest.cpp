#include "manifest.hpp"

#include "../job/file_pieces.hpp"
#include "../job/job_manifest.hpp"
#include "dqskin/version.hpp"

#include <nlohmann/json.hpp>

namespace dqskin::bake_detail {

std::string write_manifest(const std::vector<InputPlan>& plans, const BakeOptions& options, const BakeReport& report) {
  using nlohmann::json;
  json inputs = json::array();
  for (size_t i = 0; i < plans.size(); ++i) {
    const InputPlan& plan = plans[i];
    json in = job_manifest::input_record(plan, report.inputs[i].error);
    for (size_t c = 0; c < plan.clips.size(); ++c) {
      const ClipPlan& clip = plan.clips[c];
      json checks = json::object(), shares = json::object();
      for (const TextureCheck& k : report.checks)
        if (k.input == plan.path && k.clip == clip.name && !k.share.empty())
          shares[k.texture] = json::parse(k.share);  // a slice's: the merge adds them up
        else if (k.input == plan.path && k.clip == clip.name)
          checks[k.texture] = {{"max_error", k.max_error},
                               {"p99_error", k.p99_error},
                               {"max_midpoint_error", k.max_midpoint_error},
                               {"p99_midpoint_error", k.p99_midpoint_error},
                               {"max_normal_degrees", k.max_normal_degrees},
                               {"max_midpoint_normal_degrees", k.max_midpoint_normal_degrees},
                               {"samples", k.samples}};
      json& record = in["animations"][c];
      if (!checks.empty()) record["decode_check"] = std::move(checks);
      if (!shares.empty()) record["decode_check_share"] = std::move(shares);
      for (const MorphCheck& m : report.morphs)
        if (m.input == plan.path && m.clip == clip.name)
          record["morph"] = {{"frames", m.frames},
                             {"keyframes", m.keyframes},
                             {"max_error", m.max_error},
                             {"max_normal_degrees", m.max_normal_degrees},
                             {"bytes", m.bytes},
                             {"sparse_accessors", m.sparse_accessors},
                             {"quantized", m.quantized}};
    }
    inputs.push_back(std::move(in));
  }
  json outputs = json::array(), pieces = json::array();
  for (const BakeOutput& out : report.outputs) {
    outputs.push_back({{"path", out.path}, {"size", out.size}, {"sha256", out.sha256}});
    // Pieces of files the merge assembles, with what it needs to know of each (file_pieces.hpp).
    const std::optional<FilePiece> piece = file_piece(out.path);
    if (!piece) continue;
    json p = {{"path", out.path}, {"whole", piece->whole}, {"splice", to_string(piece->kind)}};
    if (piece->kind == FilePiece::Kind::kExrRows) {
      p["rows"] = {piece->first_row, piece->end_row};
    } else {
      p["texture"] = piece->texture;
      const std::string folder = piece->whole.substr(0, piece->whole.rfind('/'));
      for (size_t i = 0; i < plans.size(); ++i)
        for (size_t c = 0; c < plans[i].clips.size(); ++c)
          if (plans[i].clips[c].folder == folder) p["input"] = i, p["animation"] = c;
    }
    pieces.push_back(std::move(p));
  }

  json formats = json::array();
  for (const auto& [bit, name] : {std::pair{BakeFormat::kGlb, "glb"}, {BakeFormat::kPly, "ply"}, {BakeFormat::kObj, "obj"},
                                  {BakeFormat::kVat, "vat"}, {BakeFormat::kBones, "bones"}, {BakeFormat::kMorph, "morph"}})
    if (options.formats & unsigned(bit)) formats.push_back(name);

  json manifest = {
      {"tool", {{"name", "dqskin"}, {"version", kVersion}}},
      {"backend", {{"name", report.gpu.backend}, {"renderer", report.gpu.renderer}, {"gl_version", report.gpu.version}}},
      {"mode", to_string(options.mode)},
      {"formats", formats},
      {"shard", {{"index", options.plan.shard.index}, {"count", options.plan.shard.count}}},
      {"inputs", inputs},
      {"outputs", outputs},
  };
  // Only a shard with pieces lists them: other manifests stay as they were.
  if (!pieces.empty()) manifest["pieces"] = std::move(pieces);
  // Where the glb frames' images went, only where glb frames are written: other manifests stay as they were.
  if (options.formats & unsigned(BakeFormat::kGlb)) manifest["glb_images"] = to_string(options.glb_images);
  // --max-influences only where given: the manifests of other runs stay as they were.
  if (options.plan.load.max_influences > 0) manifest["max_influences"] = options.plan.load.max_influences;
  // Texture settings only where textures are written: the manifests of mesh bakes stay as they were.
  if (options.formats & (unsigned(BakeFormat::kVat) | unsigned(BakeFormat::kBones))) {
    const TextureOptions& t = options.textures;
    json textures = {{"vat_profile", t.vat_profile}, {"bones_profile", t.bones_profile}};
    if (!t.encoding.empty()) textures["encoding"] = t.encoding;
    if (!t.normals.empty()) textures["normals"] = t.normals;
    if (!t.exr_compression.empty()) textures["exr_compression"] = t.exr_compression;
    if (t.max_size) textures["max_size"] = t.max_size;
    if (t.pot) textures["pot"] = true;
    if (t.max_bytes > 0) textures["max_bytes"] = t.max_bytes;
    if (t.max_error > 0) {
      textures["max_error"] = t.max_error;
      textures["max_error_relative"] = t.max_error_relative;
    }
    textures["decode_check"] = t.check;
    manifest["textures"] = std::move(textures);
  }
  // Morph settings only where the morph animation is written; its budget is --max-error, as for textures.
  if (options.formats & unsigned(BakeFormat::kMorph)) {
    json morph = {{"quantize", options.morph.quantize}};
    if (options.textures.max_error > 0) {
      morph["max_error"] = options.textures.max_error;
      morph["max_error_relative"] = options.textures.max_error_relative;
    }
    manifest["morph"] = std::move(morph);
  }
  return job_manifest::write(options.plan.out_dir, job_manifest::file_name("manifest", options.plan.shard), manifest);
}

}  // namespace dqskin::bake_detail
