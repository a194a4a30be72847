// `dqskin report` as a library call: inputs planned by the job layer, each measured (measure_input.cpp),
// then its contact sheets drawn and report.json and report.html written, all committed together through
// the input's journal, so that a failed or interrupted input leaves nothing.
#include "dqskin/report.hpp"

#include "measure_input.hpp"
#include "report_html.hpp"
#include "report_json.hpp"
#include "worst_frames_sheet.hpp"
#include "../base/leftover_files.hpp"

#include "dqskin/atomic_file.hpp"
#include "dqskin/error.hpp"
#include "dqskin/image_output.hpp"
#include "../job/job_plan.hpp"
#include "../job/job_run.hpp"
#include "../job/output_folder.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <iterator>

namespace dqskin {

namespace report_detail {
namespace {

using Clock = std::chrono::steady_clock;

// The `count` frames with the largest values, in frame order (the earlier frame first on ties), each at
// least a gap of frames/(2·count) from the others: a peak spans several frames, and three neighbours of
// one peak would show one pose three times where the clip has other bad moments. The gap is relaxed to
// no gap when the clip is too short to keep it.
std::vector<size_t> worst_frames(const std::vector<double>& values, size_t count) {
  std::vector<size_t> order(values.size());
  for (size_t f = 0; f < order.size(); ++f) order[f] = f;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return values[a] > values[b]; });
  count = std::min(count, order.size());
  std::vector<size_t> chosen;
  for (size_t gap = std::max<size_t>(1, values.size() / (2 * std::max<size_t>(count, 1)));; gap = 1) {
    chosen.clear();
    for (size_t f : order) {
      if (chosen.size() == count) break;
      const bool apart = std::all_of(chosen.begin(), chosen.end(), [&](size_t c) { return (f > c ? f - c : c - f) >= gap; });
      if (apart) chosen.push_back(f);
    }
    if (chosen.size() == count || gap == 1) break;
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

// The bytes of a file just written, to embed it in the page exactly as it lies beside it. Throws OutputError.
std::vector<uint8_t> read_back(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) throw OutputError(path + ": cannot be read back");
  return bytes;
}

// The contact sheets of an input: per clip its worst frames, drawn on `context` and written at once to a
// temporary in `folder`, appended to `files` (so that one sheet's pixels are held at a time, not every
// clip's); records each in its clip. Returns the PNGs' bytes, for the page to embed.
std::vector<EmbeddedImage> contact_sheets(GpuContext& context, const InputPlan& input, const ReportOptions& options,
                                          InputData& data, const std::string& folder,
                                          std::vector<std::unique_ptr<AtomicFile>>& files) {
  std::vector<EmbeddedImage> out;
  for (size_t c = 0; c < data.clips.size(); ++c) {
    check_cancelled(options.cancel);
    ClipData& clip = data.clips[c];
    ClipImage image;
    // Named as the clip's folder in a bake (job_plan.hpp), which the planner keeps unique among the input's
    // clips: "<stem>/<anim>" gives worst_<anim>.png.
    const std::string& clip_folder = input.clips[c].folder;
    image.file = "worst_" + clip_folder.substr(std::min(clip_folder.size(), input.stem.size() + 1)) + ".png";
    image.frames = worst_frames(clip.worst_lbs_dib, size_t(options.worst_frames));
    image.scale = clip.lbs_dqs_max;
    WorstFrames frames{*input.asset, input.instances, input.clips[c].clip, {}, image.scale, options.image_size};
    for (size_t f : image.frames) frames.times.push_back(clip.times[f]);
    AtomicFile& file = *files.emplace_back(std::make_unique<AtomicFile>(folder + "/" + image.file, false));
    write_image(file, worst_frames_sheet(context, frames), ImageFormat::kPng);
    out.push_back({image.file, read_back(file.temporary())});
    clip.image = image;
  }
  return out;
}

}  // namespace
}  // namespace report_detail

bool ReportResult::any_failed() const {
  return std::any_of(inputs.begin(), inputs.end(), [](const InputResult& r) { return !r.error.empty(); });
}

ReportResult report(const std::vector<std::string>& inputs, const ReportOptions& options,
                    const std::function<void(const JobProgress&)>& progress) {
  using namespace report_detail;
  const Clock::time_point start = Clock::now();
  OutputFolder out_folder(options.plan.out_dir);  // before any check, as the command always made it
  if (options.worst_frames < 1 || options.worst_frames > 16) throw InputError("--worst-frames must be 1 to 16");
  if (options.image_size < 16 || options.image_size > 4096) throw InputError("--image-size must be 16 to 4096 pixels");
  const ReportThresholds& t = options.thresholds;
  if (!(t.tolerance >= 0) || !(t.twist_degrees >= 0) || !(t.candy_wrapper >= 0) || !(t.dqs_bulge >= 0) ||
      !std::isfinite(t.tolerance) || !std::isfinite(t.twist_degrees) || !std::isfinite(t.candy_wrapper) || !std::isfinite(t.dqs_bulge))
    throw InputError("thresholds must be finite and not negative");

  // Each input's report.json covers all its animations: there is no part of it for a shard to make.
  if (!options.plan.shard.whole()) throw InputError("a report is made whole; it cannot be sharded");

  double load_seconds = 0;
  const std::vector<InputPlan> plans = plan_inputs(inputs, options.plan, load_seconds);

  ReportResult result;
  for (const InputPlan& plan : plans)
    if (!plan.skins.empty())
      for (const ClipPlan& clip : plan.clips) result.frames_total += clip.times.size();
  JobContext context(options.backend);
  ProgressCounter counter(result.frames_total, progress);
  size_t outputs_before = 0, verdicts_before = 0;
  result.inputs = for_each_input(
      plans,
      [&](const InputPlan& plan, OutputJournal& journal, InputResult& input_result) {
        outputs_before = result.outputs.size(), verdicts_before = result.verdicts.size();
        // lbs, dqs and dib agree on a file without a skin: there is nothing to compare, and a batch goes on
        // (as bake bakes such a file) with a warning instead of failing it.
        if (plan.skins.empty()) {
          input_result.warnings.emplace_back("no skinned mesh in the scene: nothing to report; no report is written for it");
          return;
        }
        InputData data = measure_input(plan, options, counter);
        // A report is one output: its sheets, report.json and report.html are written to temporaries and
        // committed together once all are complete, so that a failure or a signal leaves none of them.
        const std::string folder = options.plan.out_dir + "/" + plan.stem;
        journal.make_folders(folder);
        std::vector<std::unique_ptr<AtomicFile>> files;
        {
          const std::vector<EmbeddedImage> embedded = contact_sheets(context.get(), plan, options, data, folder, files);
          const nlohmann::json doc = report_json(data, options);
          write_report_json(doc, *files.emplace_back(std::make_unique<AtomicFile>(folder + "/report.json")));
          AtomicFile& html = *files.emplace_back(std::make_unique<AtomicFile>(folder + "/report.html"));
          write_report_html(doc, embedded, [&html](std::string_view piece) { html.write(std::span<const char>(piece.data(), piece.size())); });
        }
        check_cancelled(options.cancel);
        std::vector<std::string> names;
        for (const std::unique_ptr<AtomicFile>& file : files) {
          file->commit({Overwrite::kReplace, &journal});
          names.push_back(std::filesystem::path(file->path()).filename().string());
          result.outputs.push_back(plan.stem + "/" + names.back());
        }
        leftover_files::remove_for(folder, names);  // what a killed run of this report left beside them
        result.verdicts.push_back(data.verdict.text);
        for (const ClipData& clip : data.clips) input_result.frames += clip.times.size();
      },
      [&](const InputPlan&) {
        result.outputs.resize(outputs_before);
        result.verdicts.resize(verdicts_before);
      });
  std::sort(result.outputs.begin(), result.outputs.end());
  out_folder.keep_if_any_succeeded(result.inputs);
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace dqskin
