// The planning flags of the commands that walk inputs × animations × frames (commands.hpp PlanSettings):
// bake, render and report read -o, the frame selection, the loading flags, --scene and --shard here, the
// same way, into one dqskin/job.hpp PlanOptions.
#include "commands.hpp"

#include "dqskin/error.hpp"

namespace dqskin::cli {

void add_plan_settings(CLI::App& command, PlanSettings& settings, const char* verb) {
  command.add_option("-o,--out", settings.out_dir, "Output folder (created when missing)")->type_name("OUTDIR");
  add_frame_selection(command, settings.selection, verb);
  add_load_settings(command, settings.load);
  add_max_influences(command, settings.load);
}

void add_scene_and_shard(CLI::App& command, PlanSettings& settings, const char* shard_help) {
  command.add_option("--scene", settings.scene, "Scene index (default: the file's default scene)")->type_name("INDEX");
  if (shard_help) command.add_option("--shard", settings.shard, shard_help)->type_name("I/N");
}

PlanOptions to_plan_options(const PlanSettings& settings) {
  PlanOptions plan;
  plan.out_dir = settings.out_dir;
  plan.load = to_load_options(settings.load);
  plan.clips = settings.selection.anim;
  plan.frames = to_frame_spec(settings.selection);
  plan.scene = settings.scene;
  if (!settings.shard.empty()) plan.shard = parse_shard(settings.shard);
  return plan;
}

}  // namespace dqskin::cli
