// `dqskin report` as a library call: every clip of the inputs deformed with lbs, dqs and dib (the exact
// reference), measured per joint region and frame (displacement between the blends, cross-section area
// around the joint's axis, volume of closed meshes, twist and bend, antipodal flips), judged per joint and
// per asset, and written as report.json with a contact sheet of each clip's worst frames. The page
// docs/commands/report.md defines every figure. No JSON, GL or tinygltf type appears here.
#pragma once

#include "dqskin/animation.hpp"
#include "dqskin/gpu_context.hpp"
#include "dqskin/job.hpp"
#include "dqskin/load.hpp"

#include <atomic>
#include <functional>
#include <string>
#include <vector>

namespace dqskin {

// The thresholds of the verdicts (docs/commands/report.md, "Verdicts").
struct ReportThresholds {
  // lbs-fine: lbs–dib max at most this; a fraction of the rest-pose diagonal when tolerance_relative,
  // else scene units (--tolerance 0.5% or 0.002).
  double tolerance = 0.005;
  bool tolerance_relative = true;
  double twist_degrees = 150;   // add-twist-joints: |twist| at least this
  double candy_wrapper = 0.3;   // use-dqs: candy-wrapper index at least this (or dqs within the tolerance)
  double dqs_bulge = 0.1;       // dqs-bulges: bulge at least this
};

struct ReportOptions {
  std::string out_dir;
  LoadOptions load;
  std::string clips = "all";
  FrameSpec frames;
  int scene = -1;
  ReportThresholds thresholds;
  int image_size = 320;      // contact-sheet cell (the render), pixels square
  int worst_frames = 3;      // frames per contact sheet
  Backend backend = Backend::kAuto;  // the context that draws the contact sheets
  // lbs and dqs on the fast float CPU deformer instead of the double reference (dib always runs there):
  // faster, and the figures move by float rounding (docs/commands/report.md).
  bool fast_cpu = false;
  const std::atomic<bool>* cancel = nullptr;
};

struct ReportResult {
  std::vector<InputResult> inputs;   // error empty when the input was reported
  std::vector<std::string> outputs;  // files written, relative to out_dir, sorted
  std::vector<std::string> verdicts; // per reported input: its asset verdict's text
  size_t frames_total = 0;           // frames measured over all inputs (each deformed three times)
  double wall_seconds = 0;
  bool any_failed() const;
};

// Reports every input (a failing input leaves nothing and the rest go on). Throws NoGpuContext when no
// context can be made for the contact sheets, JobCancelled when options.cancel was set, InputError for
// options that cannot work. `progress` is called as frames are measured.
ReportResult report(const std::vector<std::string>& inputs, const ReportOptions& options,
                    const std::function<void(const JobProgress&)>& progress = {});

}  // namespace dqskin
