// The dqskin commands. Each command file (<name>_command.cpp) holds its settings, declares its flags and
// runs; main.cpp only assembles them. A new command is a new file (listed in app/CMakeLists.txt's
// dqskin_commands) and one line in main.cpp.
#pragma once

#include "dqskin/animation.hpp"
#include "dqskin/job.hpp"
#include "dqskin/load.hpp"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace dqskin::cli {

// A command as main.cpp sees it: its subcommand (parsed() when the user named it) and how to run it with
// the flags CLI11 parsed. run() returns an ExitCode.
struct Command {
  CLI::App* cli = nullptr;
  std::function<int()> run;
};

// The whole command line (main.cpp): parses argv, runs the command named and returns its ExitCode.
int run_cli(int argc, const char* const* argv);

// A long option of a command as the command line parses it (for the Python module's keyword arguments):
// its name without dashes, whether it is a flag (no value), and whether it takes several values
// (--resource-root A B, --viewing D W P) rather than one.
struct OptionShape {
  std::string name;
  bool flag = false;
  bool several = false;
};
// The options of command `name` ("bake"), in --help's order; none for an unknown command.
std::vector<OptionShape> command_options(const std::string& name);

// Each adds its subcommand and flags to `app`, in the order --help lists them.
Command add_info_command(CLI::App& app);
Command add_bench_command(CLI::App& app);
Command add_bake_command(CLI::App& app);
Command add_render_command(CLI::App& app);
Command add_diff_command(CLI::App& app);
Command add_report_command(CLI::App& app);
Command add_lint_command(CLI::App& app);
Command add_verify_command(CLI::App& app);
Command add_merge_command(CLI::App& app);
Command add_optimize_command(CLI::App& app);

// How every command that reads glTF files reads them (--resource-root, --max-memory), shared so that info,
// bake and render read the same flags the same way.
struct LoadSettings {
  std::vector<std::string> resource_roots;
  std::string max_memory = "2G";
  int max_influences = 0;  // --max-influences of the commands that deform; 0: every influence
};

// Adds the LoadSettings flags to a command.
void add_load_settings(CLI::App& command, LoadSettings& settings);

// Adds --max-influences, for the commands that deform (bake, render, report, diff): LoadOptions::max_influences.
void add_max_influences(CLI::App& command, LoadSettings& settings);

// Adds --max-memory alone, for the commands that read no glTF file (verify, merge).
void add_max_memory(CLI::App& command, std::string& max_memory);

// The --max-memory of a parsed command, given or its default (2G); none for a command without the flag
// (bench). run_cli sets it as the command's MemoryCeiling (dqskin/memory_ceiling.hpp), so that the command
// holds it, whatever allocates. Throws InputError for a size that is not one.
std::optional<uint64_t> max_memory_of(const CLI::App& command);

// The LoadOptions they ask for. Throws InputError for a size that is not one, or a root that is not a folder.
LoadOptions to_load_options(const LoadSettings& settings);

// Which animations and frames a command works on (--anim, --fps, --frames, --keys, --times), shared by
// bake, render, report and diff so that all read the same flags the same way.
struct FrameSelection {
  std::string anim = "all";
  std::optional<double> fps;  // none: 30 (FrameSpec's grid), or diff's key times and midpoints
  std::string frames, times;
  bool keys = false;
  // Whether a flag chose the frames (diff samples its own default times otherwise).
  bool chosen() const { return fps || !frames.empty() || !times.empty() || keys; }
};

// Adds the FrameSelection flags to a command; `verb` goes into the help ("Animation to bake: …"). With
// `grid_default`, --help shows the fps grid (30) as --fps's default; diff, whose default is other times,
// passes false.
void add_frame_selection(CLI::App& command, FrameSelection& selection, const char* verb, bool grid_default = true);

// The FrameSpec they ask for (fps 30 unless given). Throws InputError for a bad range or list, or more than
// one way given.
FrameSpec to_frame_spec(const FrameSelection& selection);

// What a job is planned from (dqskin/job.hpp PlanOptions): -o, the frames, the loading flags, --scene and
// --shard, shared by bake, render and report so that the three read the same flags the same way.
struct PlanSettings {
  std::string out_dir;
  FrameSelection selection;
  LoadSettings load;
  int scene = -1;
  std::string shard;  // "I/N"; empty: the whole job
};

// Adds -o, the FrameSelection flags (`verb` in their help), the LoadSettings flags and --max-influences, in
// the order --help lists them.
void add_plan_settings(CLI::App& command, PlanSettings& settings, const char* verb);

// Adds --scene and, with a `shard_help`, --shard (report makes whole reports: it has none). Separate from
// add_plan_settings because --help lists them after the command's own blending and backend flags.
void add_scene_and_shard(CLI::App& command, PlanSettings& settings, const char* shard_help = nullptr);

// The PlanOptions they ask for. Throws InputError for a bad size, root, frame selection or shard.
PlanOptions to_plan_options(const PlanSettings& settings);

// A length in scene units ("0.002") or a percentage of a bounding-box diagonal ("0.5%", as the fraction
// 0.005 with relative set): bake's --max-error and report's --tolerance.
struct LengthOrPercent {
  double value = 0;
  bool relative = false;
};

// Parses `text`: a finite number, more than zero (or not negative with allow_zero), with an optional '%'.
// Throws InputError(problem) otherwise.
LengthOrPercent parse_length_or_percent(const std::string& text, bool allow_zero, const std::string& problem);

}  // namespace dqskin::cli
