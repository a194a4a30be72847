#include "job_plan.hpp"

#include "../base/byte_size.hpp"
#include "dqskin/error.hpp"
#include "dqskin/memory_ceiling.hpp"
#include "dqskin/load.hpp"
#include "../base/file_kind.hpp"

#include <unistd.h>

#include <chrono>
#include <climits>
#include <cstdio>
#include <map>
#include <set>

namespace dqskin {
namespace {

std::string stem_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const size_t dot = name.find_last_of('.');
  if (dot != std::string::npos && dot > 0) name.resize(dot);
  return safe_name(name);
}

int digits(size_t n) {
  int d = 1;
  while (n >= 10) n /= 10, ++d;
  return d;
}

// The longest file name the output's file system takes, asked of the output folder or, before it exists,
// its nearest ancestor that does.
size_t longest_name(const std::string& out_dir) {
  const long n = ::pathconf(nearest_existing(out_dir).c_str(), _PC_NAME_MAX);
  return n > 0 ? size_t(n) : 255;
}

// What a name looks like in a message: printable, and at most 40 characters of it.
std::string shortened(const std::string& name) { return name.size() <= 40 ? name : name.substr(0, 40) + "..."; }

// Names that the file system would refuse only when the first file is written (an animation name of 254
// bytes, with a suffix, makes a folder name of 256) are refused before anything is written. Frame and
// texture names are short; their temporaries add about 30 bytes, which the path-length check allows for.
void check_name_lengths(const std::string& out_dir, const ClipPlan& clip, const std::string& stem, size_t name_max) {
  const std::string anim = clip.folder.substr(stem.size() + 1);
  for (const auto& [name, what] : {std::pair{stem, "the input's file name"}, std::pair{anim, "the animation's name"}})
    if (name.size() > name_max)
      throw InputError(std::string(what) + " makes the folder name '" + shortened(name) + "' " +
                       std::to_string(name.size()) + " bytes long; the output's file system takes at most " +
                       std::to_string(name_max));
  constexpr size_t kLongestFile = 96;  // "frame_NNNN.glb", "bones_skinK.json", "sheet_shardIofN.png" + temporary
  const size_t path = out_dir.size() + 1 + clip.folder.size() + 1 + kLongestFile;
  if (path >= PATH_MAX)
    throw InputError("the output paths under " + shortened(clip.folder) + " would be about " + std::to_string(path) +
                     " bytes long; the system takes at most " + std::to_string(PATH_MAX));
}

// One deformed frame holds every instance's vertices: a small file whose nodes draw one large mesh a
// thousand times would need a thousand times its memory per frame. The CPU reference keeps positions,
// normals and tangents in double (80 bytes a vertex), a batch of frames in float beside them.
void check_frame_size(const Asset& asset, const std::vector<MeshInstance>& instances, uint64_t max_memory) {
  constexpr uint64_t kBytesPerVertex = 80 + 40;
  uint64_t vertices = 0;
  for (const MeshInstance& inst : instances)
    for (const Primitive& p : asset.meshes[size_t(inst.mesh)].primitives) vertices += p.vertex_count();
  if (vertices > max_memory / kBytesPerVertex)
    throw InputError("the scene draws " + std::to_string(vertices) + " vertices a frame (" +
                     std::to_string(instances.size()) + " mesh instances); deforming one frame needs about " +
                     byte_size(vertices * kBytesPerVertex) + ", more than --max-memory " + byte_size(max_memory));
}

// "--frames 0:59" or "--frames 0:59:2", as the user gave it.
std::string frames_flag(const FrameSpec& spec) {
  char text[64];
  if (spec.step != 1)
    std::snprintf(text, sizeof text, "--frames %d:%d:%d", spec.first.value_or(0), spec.last.value_or(0), spec.step);
  else
    std::snprintf(text, sizeof text, "--frames %d:%d", spec.first.value_or(0), spec.last.value_or(0));
  return text;
}

// "'Walk' (0.4 s) has frames 0..12 at 30 fps"
std::string clip_frames(const Clip& clip, const FrameSpec& spec, int count) {
  char text[96];
  std::snprintf(text, sizeof text, " (%.3g s) has frames 0..%d at %.6g fps", clip.last_key, count - 1, spec.fps);
  return "animation '" + clip.name + "'" + text;
}

// The frames of one clip that --frames A:B asks for. A batch goes on past a clip shorter than B: the clip
// gives the frames it has (a warning names it), and one that has none of them is left out (`times` empty,
// a warning too). Without --frames, or with --keys or --times, every frame frame_times gives.
std::vector<double> clip_times(const Clip& clip, const FrameSpec& spec, std::vector<std::string>& warnings) {
  if (!spec.last || spec.keys || !spec.times.empty()) return frame_times(clip, spec);
  const int count = grid_frame_count(clip, spec);
  if (*spec.last < count) return frame_times(clip, spec);
  if (spec.first.value_or(0) >= count) {
    warnings.push_back(clip_frames(clip, spec, count) + ": " + frames_flag(spec) + " asks for none of them; it is left out");
    return {};
  }
  FrameSpec shorter = spec;
  const int first = spec.first.value_or(0);
  shorter.last = first + (count - 1 - first) / spec.step * spec.step;  // the last frame of the range it has
  warnings.push_back(clip_frames(clip, spec, count) + ", so " + frames_flag(spec) + " gives its frames " +
                     std::to_string(first) + ".." + std::to_string(*shorter.last));
  return frame_times(clip, shorter);
}

}  // namespace

std::string safe_name(const std::string& name) {
  std::string out = name;
  for (char& c : out)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.'))
      c = '_';
  // Never empty, hidden, "." or "..".
  if (out.empty()) out.push_back('_');
  if (out[0] == '.') out[0] = '_';
  return out;
}

std::string ClipPlan::frame_file(size_t frame, const char* extension) const {
  char number[32];
  std::snprintf(number, sizeof number, "%0*d", number_width, numbers[frame]);
  return folder + "/frame_" + number + "." + extension;
}

std::vector<size_t> ClipPlan::my_frames() const {
  std::vector<size_t> out;
  for (size_t f = 0; f < frame_mine.size(); ++f)
    if (frame_mine[f]) out.push_back(f);
  return out;
}

std::vector<InputPlan> plan_inputs(const std::vector<std::string>& inputs, const PlanOptions& options, double& load_seconds) {
  std::vector<InputPlan> plans;
  const size_t name_max = longest_name(options.out_dir);
  std::map<std::string, std::string> stems;  // output folder → the input that writes it
  size_t frame_unit = 0, clip_unit = 0;
  for (const std::string& path : inputs) {
    InputPlan plan;
    plan.path = path;
    plan.stem = stem_of(path);
    if (const auto [it, fresh] = stems.emplace(plan.stem, path); !fresh)
      throw InputError("inputs " + it->second + " and " + path + " would both write to " + options.out_dir + "/" +
                       plan.stem + "; give them different output folders");
    try {
      const auto start = std::chrono::steady_clock::now();
      plan.asset = std::make_unique<Asset>(load_asset(path, options.load));
      load_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const Asset& asset = *plan.asset;
      plan.scene = choose_scene(asset, options.scene);
      plan.instances = mesh_instances(asset, plan.scene);
      if (plan.instances.empty()) throw InputError("the scene draws no meshes");
      check_frame_size(asset, plan.instances, options.load.max_memory);
      std::set<int> skins;
      for (const MeshInstance& inst : plan.instances)
        if (inst.skin >= 0) skins.insert(inst.skin);
      plan.skins.assign(skins.begin(), skins.end());

      std::vector<const Clip*> clips;
      if (asset.clips.empty() && (options.clips == "all" || options.clips == "0")) {
        // A file without animations bakes its rest pose; so does "--anim 0", the first animation there is,
        // so that one command line serves a batch of files with and without animations.
        clips.push_back(nullptr);
        if (options.clips == "0") plan.asset->warnings.push_back("the file has no animations; --anim 0 takes its rest pose");
      } else {
        for (size_t c : select_clips(asset, options.clips)) clips.push_back(&asset.clips[c]);
      }
      std::set<std::string> folders;
      for (size_t c = 0; c < clips.size(); ++c) {
        ClipPlan cp;
        cp.clip = clips[c];
        cp.name = cp.clip ? cp.clip->name : "rest";
        const size_t index = cp.clip ? size_t(cp.clip - asset.clips.data()) : 0;
        std::string folder = cp.clip ? (cp.clip->name.empty() ? "animation_" + std::to_string(index) : safe_name(cp.name)) : "rest";
        // Two clips of one name: the later gets its index, and a count after it should another clip be
        // named so already ("Walk_2", "Walk", "Walk").
        if (!folders.insert(folder).second) {
          const std::string base = folder + "_" + std::to_string(index);
          folder = base;
          for (size_t k = 2; !folders.insert(folder).second; ++k) folder = base + "_" + std::to_string(k);
        }
        cp.folder = plan.stem;
        cp.folder.append("/").append(folder);
        check_name_lengths(options.out_dir, cp, plan.stem, name_max);
        if (cp.clip) {
          cp.times = clip_times(*cp.clip, options.frames, plan.asset->warnings);
          if (cp.times.empty()) continue;  // none of --frames A:B is in it (warned); its folder name stays taken
        } else {
          cp.times = options.frames.times.empty() ? std::vector<double>{0.0} : options.frames.times;
        }
        const bool grid = cp.clip && options.frames.times.empty() && !options.frames.keys;
        cp.fps = grid ? options.frames.fps : 0.0;
        for (size_t f = 0; f < cp.times.size(); ++f)
          cp.numbers.push_back(grid ? options.frames.first.value_or(0) + int(f) * options.frames.step : int(f));
        cp.number_width = std::max(4, digits(size_t(cp.numbers.empty() ? 0 : cp.numbers.back())));
        plan.clips.push_back(std::move(cp));
      }
      if (plan.clips.empty()) {  // every clip was left out: the longest says what --frames could ask for
        const Clip* longest = clips.front();
        for (const Clip* c : clips)
          if (c->last_key > longest->last_key) longest = c;
        throw InputError(frames_flag(options.frames) + " asks for frames past the end of every animation; the longest, " +
                         clip_frames(*longest, options.frames, grid_frame_count(*longest, options.frames)));
      }
    } catch (const std::bad_alloc&) {
      const MemoryCeilingLifted lifted;  // the message and the empty plan allocate
      plan = InputPlan{path, plan.stem, nullptr, -1, {}, {}, {}, out_of_memory_message()};
    } catch (const std::exception& e) {
      plan = InputPlan{path, plan.stem, nullptr, -1, {}, {}, {}, e.what()};
    }
    // Units are numbered after the input is known to load, so a failing input takes none.
    for (ClipPlan& cp : plan.clips) {
      cp.clip_mine = options.shard.owns(clip_unit++);
      cp.morph_mine = cp.clip_mine;
      cp.texture_end = cp.clip_mine ? cp.times.size() : 0;
      for (size_t f = 0; f < cp.times.size(); ++f) cp.frame_mine.push_back(options.shard.owns(frame_unit++));
    }
    plans.push_back(std::move(plan));
  }
  return plans;
}

}  // namespace dqskin
