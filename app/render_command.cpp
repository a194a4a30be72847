// `dqskin render INPUT… -o OUTDIR`: every frame of the inputs' animations drawn offscreen into PNG or EXR
// images, with bake's frame, animation, mode, backend and shard flags and its exit statuses.
#include "commands.hpp"
#include "console.hpp"
#include "default_input.hpp"
#include "exit_codes.hpp"
#include "interrupt.hpp"

#include "dqskin/error.hpp"
#include "dqskin/output_journal.hpp"
#include "dqskin/stderr_lock.hpp"
#include "dqskin/render.hpp"

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace dqskin::cli {
namespace {

// "WxH", each side 1 to 16384.
void parse_size(const std::string& text, RendererOptions& o) {
  const size_t x = text.find('x');
  auto side = [&](const std::string& s) {
    if (s.empty() || s.size() > 5 || s.find_first_not_of("0123456789") != std::string::npos)
      throw InputError("--size '" + text + "' is not WxH (e.g. 512x512)");
    const int n = std::stoi(s);
    if (n < 1 || n > 16384) throw InputError("--size '" + text + "': each side must be 1 to 16384 pixels");
    return n;
  };
  if (x == std::string::npos) throw InputError("--size '" + text + "' is not WxH (e.g. 512x512)");
  o.width = side(text.substr(0, x));
  o.height = side(text.substr(x + 1));
}

// sRGB 8-bit code to linear, so that "--background #336699" looks like that color in the PNG.
float srgb_to_linear(double s) { return float(s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4)); }

// "R,G,B" or "R,G,B,A" in sRGB 0..1 (alpha linear), or "#RRGGBB" / "#RRGGBBAA".
glm::vec4 parse_background(const std::string& text) {
  const std::string problem = "--background '" + text + "' is not R,G,B[,A] (0 to 1, sRGB) or #RRGGBB[AA]";
  std::vector<double> c;
  if (!text.empty() && text[0] == '#') {
    const std::string hex = text.substr(1);
    if ((hex.size() != 6 && hex.size() != 8) || hex.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos)
      throw InputError(problem);
    for (size_t i = 0; i < hex.size(); i += 2) c.push_back(double(std::stoi(hex.substr(i, 2), nullptr, 16)) / 255.0);
  } else {
    std::stringstream in(text);
    std::string part;
    while (std::getline(in, part, ',')) {
      size_t used = 0;
      double v = 0;
      try {
        v = std::stod(part, &used);
      } catch (const std::exception&) {
        throw InputError(problem);
      }
      if (used != part.size() || !(v >= 0 && v <= 1)) throw InputError(problem);
      c.push_back(v);
    }
    if (c.size() != 3 && c.size() != 4) throw InputError(problem);
  }
  return {srgb_to_linear(c[0]), srgb_to_linear(c[1]), srgb_to_linear(c[2]), float(c.size() == 4 ? c[3] : 1.0)};
}

RenderOptions to_options(const RenderSettings& s) {
  RenderOptions o;
  o.out_dir = s.out_dir;
  o.load = to_load_options(s.load);
  o.clips = s.selection.anim;
  o.frames = to_frame_spec(s.selection);
  if (!parse_blend_mode(s.mode, o.mode)) throw InputError("--mode '" + s.mode + "' is not one of lbs, dqs, dib");
  if (!parse_backend(s.backend, o.backend)) throw InputError(unknown_backend(s.backend));
  o.scene = s.scene;
  if (!s.shard.empty()) o.shard = parse_shard(s.shard);
  parse_size(s.size.empty() ? "512x512" : s.size, o.renderer);
  o.size_from_camera = s.size.empty();
  o.renderer.samples = s.samples;
  o.renderer.background = parse_background(s.background);
  if (!parse_shade(s.shade, o.renderer.shade)) throw InputError("--shade '" + s.shade + "' is not one of lit, normals, weights, mode-diff");
  if (o.renderer.shade == Shade::kWeights && s.joint.empty()) throw InputError("--shade weights needs --joint NAME");
  o.joint = s.joint;
  if (!parse_image_format(s.format, o.format)) throw InputError("--format '" + s.format + "' is not one of png, exr");
  if (s.yaw) o.camera.yaw = *s.yaw;
  if (s.pitch) o.camera.pitch = *s.pitch;
  if (s.fov) o.camera.fov = *s.fov;
  o.camera.distance = s.distance;
  o.camera.ortho = s.ortho;
  if (!s.camera.empty() && (s.yaw || s.pitch || s.distance || s.fov || s.ortho))
    throw InputError("--camera sets the view; it cannot be combined with --yaw, --pitch, --distance, --fov or --ortho");
  o.camera_node = s.camera;
  if (s.sheet_cell < 1 || s.sheet_cell > 4096) throw InputError("--sheet-cell " + std::to_string(s.sheet_cell) + ": must be 1 to 4096 pixels");
  o.sheet = s.sheet;
  o.sheet_cell = s.sheet_cell;
  o.gif = s.gif;
  o.overwrite = s.force ? Overwrite::kReplace : Overwrite::kRefuseDifferent;
  return o;
}

// One line per rendered frame: a JSON object, or a counter on a terminal.
void report_progress(const RenderSettings& s, const JobProgress& p, std::chrono::steady_clock::time_point start) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (s.json_progress) {
    std::cout << json_text(nlohmann::json{{"event", "progress"},         {"frames_done", p.frames_done},
                                          {"frames_total", p.frames_total}, {"input", p.input},
                                          {"animation", p.clip},          {"elapsed_s", elapsed}})
              << std::endl;
  } else if (!s.quiet && ::isatty(2)) {
    const std::lock_guard<std::mutex> lock(stderr_mutex());
    std::fprintf(stderr, "\r\033[K%zu/%zu frames  %s", p.frames_done, p.frames_total, printable(p.clip).c_str());
  }
}

}  // namespace

int run_render(const RenderSettings& given) {
  RenderSettings settings = given;
  const auto start = std::chrono::steady_clock::now();
  const bool bar = !settings.quiet && !settings.json_progress && ::isatty(2);
  auto clear_bar = [&]() {
    if (bar) std::fputs("\r\033[K", stderr);
  };
  OutputJournal out_folder;  // the output folder, when this run creates it: removed again if nothing rendered
  try {
    if (settings.inputs.empty()) settings.inputs.push_back(unpack_default_input("render", settings.out_dir, settings.quiet));
    if (settings.out_dir.empty()) throw InputError("-o OUTDIR is required when inputs are given");
    RenderOptions options = to_options(settings);
    options.cancel = catch_interrupts("render");
    out_folder.make_folders(options.out_dir);
    const RenderReport report =
        render(settings.inputs, options, [&](const JobProgress& p) { report_progress(settings, p, start); });
    clear_bar();
    print_input_messages(report.inputs, settings.quiet);
    const size_t failed = size_t(std::count_if(report.inputs.begin(), report.inputs.end(),
                                               [](const InputResult& r) { return !r.error.empty(); }));
    if (failed < report.inputs.size()) out_folder.keep();
    // mode-diff: what the heat map's top color stands for, per animation.
    nlohmann::json scales = nlohmann::json::array();
    for (const ModeDiffScale& m : report.mode_diff) {
      scales.push_back({{"input", m.input}, {"animation", m.clip}, {"max_distance", m.max_distance}});
      if (!settings.quiet && !settings.json_progress)
        std::fprintf(stderr, "mode-diff %s %s: red = %.6g (largest |lbs - %s| position distance), dark blue = 0\n",
                     printable(m.input).c_str(), printable(m.clip).c_str(), m.max_distance, settings.mode == "lbs" ? "dqs" : settings.mode.c_str());
    }
    if (settings.json_progress) {
      std::cout << json_text(nlohmann::json{{"event", "summary"},           {"mode_diff", scales},          {"frames", report.frames_total},
                                  {"files", report.outputs.size()}, {"backend", report.gpu.backend},
                                  {"renderer", report.gpu.renderer}, {"failed_inputs", failed},
                                  {"wall_s", report.wall_seconds}})
                << std::endl;
    } else if (!settings.quiet && failed < report.inputs.size()) {
      size_t frames = 0;  // not report.outputs: --sheet and --gif add files that are not frames
      for (const InputResult& in : report.inputs) frames += in.frames;
      std::fprintf(stderr, "rendered %zu frames of %zu input%s in %.2f s into %s\n", frames,
                   report.inputs.size() - failed, report.inputs.size() - failed == 1 ? "" : "s", report.wall_seconds,
                   printable(options.out_dir).c_str());
    }
    if (failed == 0) return kSuccess;
    if (!settings.quiet && failed < report.inputs.size())
      print_error(std::to_string(failed) + " of " + std::to_string(report.inputs.size()) + " inputs failed; the others rendered");
    return failed == report.inputs.size() ? kUsageOrInputError : kSomeInputsFailed;
  } catch (const JobCancelled&) {
    clear_bar();
    out_folder.roll_back();  // removes the output folder this run made only if it is still empty
    return die_of_interrupt("render");
  } catch (const NoGpuContext& e) {
    clear_bar();
    print_error(e.what());
    return kNoGlContext;
  } catch (const std::filesystem::filesystem_error& e) {
    clear_bar();
    print_error(e.path1().string(), e.code().message());
    return kUsageOrInputError;
  } catch (const std::exception& e) {
    clear_bar();
    print_error(e.what());
    return kUsageOrInputError;
  }
}

}  // namespace dqskin::cli
