// `dqskin optimize IN -o OUT.glb --max-error LENGTH|N%`: the input's animations made smaller while the
// deformed surface stays within the budget (dqskin/optimize.hpp). Prints what it did per clip (or --json),
// exit status 0, or one line and 2 for bad input.
#include "commands.hpp"
#include "console.hpp"
#include "exit_codes.hpp"
#include "interrupt.hpp"

#include "dqskin/error.hpp"
#include "dqskin/optimize.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>

namespace dqskin::cli {
namespace {

struct OptimizeSettings {
  std::string input, output, max_error, mode = "lbs";
  bool keep_keys = false, keep_channels = false, keep_interpolation = false, keep_times = false, keep_float = false, json = false;
  LoadSettings load;
};

std::string figure(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

std::string text_summary(const OptimizeSummary& s) {
  std::string t = "dqskin: optimize: wrote " + printable(s.output) + " (budget " + figure(s.budget) + ", " +
                  to_string(s.mode) + "; animation data " + std::to_string(s.animation_bytes_before) + " -> " +
                  std::to_string(s.animation_bytes_after) + " bytes, file " + std::to_string(s.file_bytes_before) +
                  " -> " + std::to_string(s.file_bytes_after) + " bytes)\n";
  for (const ClipOptimization& c : s.clips) {
    t += "  " + printable(c.name) + ": keys " + std::to_string(c.keys_before) + " -> " + std::to_string(c.keys_after) +
         ", channels " + std::to_string(c.channels_before) + " -> " + std::to_string(c.channels_after) + "; max error " +
         figure(c.max_error);
    if (c.max_error > 0) t += " at " + figure(c.max_error_time) + " s near " + printable(c.max_error_joint);
    t += ", p99 " + figure(c.p99_error) + " over " + std::to_string(c.judged_times) + " times\n";
  }
  for (const std::string& note : s.notes) t += "  note: " + printable(note) + "\n";
  return t;
}

nlohmann::json json_summary(const OptimizeSummary& s) {
  nlohmann::json clips = nlohmann::json::array();
  for (const ClipOptimization& c : s.clips)
    clips.push_back({{"name", c.name}, {"keys_before", c.keys_before}, {"keys_after", c.keys_after},
                     {"channels_before", c.channels_before}, {"channels_after", c.channels_after},
                     {"max_error", c.max_error}, {"p99_error", c.p99_error}, {"max_error_time", c.max_error_time},
                     {"max_error_joint", c.max_error_joint}, {"judged_times", c.judged_times},
                     {"scale_factor", c.scale_factor}});
  return {{"input", s.input}, {"output", s.output}, {"budget", s.budget}, {"diagonal", s.diagonal},
          {"mode", to_string(s.mode)}, {"animation_bytes_before", s.animation_bytes_before},
          {"animation_bytes_after", s.animation_bytes_after}, {"file_bytes_before", s.file_bytes_before},
          {"file_bytes_after", s.file_bytes_after}, {"clips", clips}, {"notes", s.notes}};
}

int run_optimize(OptimizeSettings& s) {
  OptimizeOptions o;
  const LengthOrPercent e = parse_length_or_percent(
      s.max_error, true, "--max-error '" + s.max_error + "' is not a length or percentage of at least 0 (0.001, 0.1%)");
  if (e.relative) o.max_error_percent = e.value * 100;
  else o.max_error = e.value;
  if (!parse_blend_mode(s.mode, o.mode) || o.mode == BlendMode::kDib)
    throw InputError("--mode '" + s.mode + "' is not one of lbs, dqs");
  if (s.output.size() < 5 || s.output.substr(s.output.size() - 4) != ".glb") throw InputError("-o must name a .glb file");
  o.remove_keys = !s.keep_keys;
  o.drop_channels = !s.keep_channels;
  o.convert_interpolation = !s.keep_interpolation;
  o.share_times = !s.keep_times;
  o.quantize_rotations = o.quantize_weights = !s.keep_float;
  o.load = to_load_options(s.load);
  o.cancel = catch_interrupts("optimize");
  const OptimizeSummary summary = optimize(s.input, s.output, o);
  if (s.json) std::cout << json_summary(summary).dump(2) << '\n';
  else std::cerr << text_summary(summary);
  return kSuccess;
}

}  // namespace

Command add_optimize_command(CLI::App& app) {
  auto settings = std::make_shared<OptimizeSettings>();
  OptimizeSettings& s = *settings;
  CLI::App* cmd = app.add_subcommand(
      "optimize",
      "Make a glTF file's animations smaller while the skinned surface stays within --max-error of the input's "
      "at every key time and midpoint, measured on the written file");
  cmd->add_option("IN", s.input, "glTF file (.gltf, .glb)")->required();
  cmd->add_option("-o,--output", s.output, "The optimized file (.glb, written atomically)")
      ->type_name("OUT.glb")
      ->required();
  cmd->add_option("--max-error", s.max_error,
                  "The budget: a length in scene units, or a percentage of the rest pose's bounding-box diagonal "
                  "(0.001, 0.1%); 0 removes only what changes nothing")
      ->type_name("LENGTH|N%")
      ->required();
  cmd->add_option("--mode", s.mode, "The skinning the file's runtime does: lbs (viewers and engines) or dqs")
      ->type_name("MODE")
      ->capture_default_str();
  cmd->add_flag("--keep-keys", s.keep_keys, "Remove no keys");
  cmd->add_flag("--keep-channels", s.keep_channels, "Drop no channel, even one that stays at the node's rest value");
  cmd->add_flag("--keep-interpolation", s.keep_interpolation,
                "Keep every channel's interpolation (else LINEAR may become STEP and CUBICSPLINE LINEAR, where smaller)");
  cmd->add_flag("--keep-times", s.keep_times,
                "Keep each channel's key times (else LINEAR channels may be resampled onto one shared grid, where smaller)");
  cmd->add_flag("--keep-float", s.keep_float,
                "Store rotations and morph weights as floats (else as normalized integers within the budget)");
  add_load_settings(*cmd, s.load);
  cmd->add_flag("--json", s.json, "Print the summary as one JSON document on stdout");
  cmd->footer(
      "Keys of LINEAR and STEP channels are removed where interpolation reproduces them, a channel that does not\n"
      "change becomes one key, and one that stays at its node's rest value goes; LINEAR becomes STEP and\n"
      "CUBICSPLINE LINEAR where that is smaller within the budget, and LINEAR channels may share one resampled grid\n"
      "of key times; float rotations and morph weights are stored as\n"
      "normalized integers (glTF 2.0 allows them for both; --keep-float keeps floats); each channel's share of the\n"
      "budget is searched for per clip and the result measured on the written file, read back, by the\n"
      "double-precision deformer. The mesh, the skin and node rest transforms are kept.\n"
      "Exit status: 0 written, 2 usage or input error (nothing written).\n"
      "Examples:\n"
      "  dqskin optimize Fox.glb -o Fox.small.glb --max-error 0.1%\n"
      "  dqskin optimize character.gltf -o character.glb --max-error 0.0005 --mode dqs --json");
  return {cmd, [settings] { return run_optimize(*settings); }};
}

}  // namespace dqskin::cli
