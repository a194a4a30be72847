// The frame-choosing flags of bake, render, report and diff (commands.hpp FrameSelection).
#include "commands.hpp"

#include "dqskin/error.hpp"

#include <sstream>

namespace dqskin::cli {

void add_frame_selection(CLI::App& command, FrameSelection& selection, const char* verb, bool grid_default) {
  command.add_option("--anim", selection.anim, std::string("Animation to ") + verb + ": all, a name, or an index")
      ->type_name("NAME|INDEX|all")
      ->capture_default_str();
  CLI::Option* fps =
      command.add_option("--fps", selection.fps, "Frames per second of the sampling grid; frame i is at i/fps seconds")
          ->type_name("FPS")
          ->check(CLI::PositiveNumber);
  if (grid_default) {
    std::ostringstream grid;
    grid << FrameSpec{}.fps;
    fps->default_str(grid.str());  // shown only: the value stays unset unless given
  }
  command.add_option("--frames", selection.frames, "Only grid frames A to B inclusive, every step-th")->type_name("A:B[:step]");
  command.add_flag("--keys", selection.keys, "Sample every key time of the animation instead of the fps grid");
  command.add_option("--times", selection.times, "Sample these times in seconds instead of the fps grid")->type_name("T,T,...");
}

FrameSpec to_frame_spec(const FrameSelection& s) {
  if (int(s.keys) + int(!s.times.empty()) + int(!s.frames.empty()) > 1)
    throw InputError("--frames, --keys and --times choose frames in different ways; give one of them");
  FrameSpec spec;
  spec.fps = s.fps.value_or(spec.fps);
  if (!s.frames.empty()) parse_frame_range(s.frames, spec);
  if (!s.times.empty()) spec.times = parse_times(s.times);
  spec.keys = s.keys;
  return spec;
}

}  // namespace dqskin::cli
