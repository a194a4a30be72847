// `dqskin info FILE…`: scenes, skinned meshes, skins, animations, morph targets and warnings per file,
// as text or one JSON document.
#include "commands.hpp"
#include "console.hpp"
#include "exit_codes.hpp"

#include "dqskin/error.hpp"
#include "dqskin/info.hpp"
#include "dqskin/load.hpp"
#include "dqskin/memory_ceiling.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>

namespace dqskin::cli {
namespace {

// The JOINTS_n attributes of `sets` influence sets, as the text report names them.
std::string influence_set_names(int sets) {
  if (sets > 2) return "JOINTS_0..JOINTS_" + std::to_string(sets - 1);
  return sets > 1 ? "JOINTS_0, JOINTS_1" : "JOINTS_0";
}

struct InfoSettings {
  std::vector<std::string> inputs;
  LoadSettings load;
  bool json = false;
};

std::string seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f s", s);
  return buf;
}

std::string join(const std::vector<std::string>& items, const char* separator) {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : separator) + s;
  return out;
}

void print_text(const std::string& path, const AssetFacts& f) {
  std::cout << printable(path) << '\n';
  std::cout << "  scenes: " << f.scenes;
  if (f.default_scene >= 0) std::cout << " (default " << f.default_scene << ")";
  std::cout << "\n  vertices: " << f.vertices << "\n  skinned meshes: " << f.skinned_meshes.size() << '\n';
  for (const SkinnedMeshFacts& m : f.skinned_meshes)
    std::cout << "    " << (m.name.empty() ? "(unnamed)" : printable(m.name)) << " (node " << m.node << ", mesh " << m.mesh
              << ", skin " << m.skin << "): " << m.vertices << " vertices, " << m.triangles << " triangles, up to "
              << m.max_influences << (m.max_influences == 1 ? " influence" : " influences") << " per vertex ("
              << influence_set_names(m.influence_sets)
              << ")\n";
  std::cout << "  skins: " << f.skins.size() << " (" << f.joint_nodes << " distinct joints)\n";
  for (size_t i = 0; i < f.skins.size(); ++i) {
    const SkinFacts& s = f.skins[i];
    std::cout << "    " << i << (s.name.empty() ? "" : " " + printable(s.name)) << ": " << s.joints << " joints, "
              << (s.non_rigid_in_bind_pose || s.non_rigid_in_animation
                      ? std::string("non-rigid (scale or shear) ") +
                            (s.non_rigid_in_bind_pose && s.non_rigid_in_animation ? "in the bind pose and animated"
                             : s.non_rigid_in_bind_pose                           ? "in the bind pose"
                                                                                  : "in animation")
                      : std::string("rigid"))
              << '\n';
  }
  std::cout << "  animations: " << f.clips.size() << '\n';
  for (size_t i = 0; i < f.clips.size(); ++i) {
    const ClipFacts& c = f.clips[i];
    std::cout << "    " << i << " " << printable(c.name) << ": " << seconds(c.duration);
    if (c.first_key > 0) std::cout << " (keys from " << seconds(c.first_key) << ")";
    std::cout << ", " << c.channels << " channels, " << join(c.interpolations, ", ") << '\n';
  }
  std::cout << "  morph targets:" << (f.morph_targets.empty() ? " none" : "") << '\n';
  for (const MorphFacts& m : f.morph_targets)
    std::cout << "    mesh " << m.mesh << (m.name.empty() ? "" : " " + printable(m.name)) << ": " << m.targets << " targets\n";
  std::cout << "  warnings:" << (f.warnings.empty() ? " none" : "") << '\n';
  for (const std::string& w : f.warnings) std::cout << "    " << printable(w) << '\n';
  // Only for a file the deforming commands refuse: what a user sees first when bake says no.
  if (f.cannot_deform.empty()) return;
  std::cout << "  cannot be deformed (bake, render, report and diff refuse it):\n";
  for (const std::string& why : f.cannot_deform) std::cout << "    " << printable(why) << '\n';
}

nlohmann::ordered_json to_json(const std::string& path, const AssetFacts& f) {
  nlohmann::ordered_json j;
  j["path"] = path;
  j["scenes"] = f.scenes;
  j["default_scene"] = f.default_scene;
  j["vertices"] = f.vertices;
  j["skinned_meshes"] = nlohmann::ordered_json::array();
  for (const SkinnedMeshFacts& m : f.skinned_meshes)
    j["skinned_meshes"].push_back({{"name", m.name}, {"node", m.node}, {"mesh", m.mesh}, {"skin", m.skin},
                                   {"vertices", m.vertices}, {"triangles", m.triangles},
                                   {"max_influences", m.max_influences}, {"influence_sets", m.influence_sets}});
  j["joint_nodes"] = f.joint_nodes;
  j["skins"] = nlohmann::ordered_json::array();
  for (const SkinFacts& s : f.skins)
    j["skins"].push_back({{"name", s.name}, {"joints", s.joints}, {"non_rigid_in_bind_pose", s.non_rigid_in_bind_pose},
                          {"non_rigid_in_animation", s.non_rigid_in_animation}});
  j["animations"] = nlohmann::ordered_json::array();
  for (const ClipFacts& c : f.clips)
    j["animations"].push_back({{"name", c.name}, {"duration", c.duration}, {"first_key", c.first_key},
                               {"channels", c.channels}, {"interpolations", c.interpolations}});
  j["morph_targets"] = nlohmann::ordered_json::array();
  for (const MorphFacts& m : f.morph_targets)
    j["morph_targets"].push_back({{"mesh", m.mesh}, {"name", m.name}, {"targets", m.targets}});
  j["warnings"] = f.warnings;
  j["cannot_deform"] = f.cannot_deform;
  return j;
}

// Prints facts about each input. Returns an ExitCode.
int run_info(const InfoSettings& settings) {
  nlohmann::ordered_json files = nlohmann::ordered_json::array();
  size_t failed = 0;
  LoadOptions options = to_load_options(settings.load);
  // info describes every file a viewer opens; what stops a deformation is listed, not refused.
  options.refuse_undeformable = false;
  for (size_t i = 0; i < settings.inputs.size(); ++i) {
    const std::string& path = settings.inputs[i];
    std::string error;
    try {
      const AssetFacts facts = describe(load_asset(path, options));
      if (settings.json) {
        files.push_back(to_json(path, facts));
      } else {
        if (i > 0) std::cout << '\n';
        print_text(path, facts);
      }
    } catch (const InputError& e) {
      error = e.what();
    } catch (const std::bad_alloc&) {
      error = out_of_memory_message();
    }
    if (error.empty()) continue;
    ++failed;
    print_error(path, error);
    if (settings.json) files.push_back({{"path", path}, {"error", error}});
  }
  if (settings.json) std::cout << json_text(nlohmann::ordered_json{{"files", files}}, 2) << '\n';
  if (failed == 0) return kSuccess;
  return failed == settings.inputs.size() ? kUsageOrInputError : kSomeInputsFailed;
}

}  // namespace

Command add_info_command(CLI::App& app) {
  auto settings = std::make_shared<InfoSettings>();
  InfoSettings& info = *settings;
  CLI::App* info_cmd = app.add_subcommand(
      "info", "Print scenes, skinned meshes, skins, animations, morph targets and warnings of glTF files");
  info_cmd->add_option("FILE", info.inputs, ".gltf or .glb files")->required();
  info_cmd->add_flag("--json", info.json, "Print one JSON document instead of text");
  add_load_settings(*info_cmd, info.load);
  return {info_cmd, [settings] { return run_info(*settings); }};
}

}  // namespace dqskin::cli
