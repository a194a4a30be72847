// The bake: plan, then per input and clip deform batch after batch (GPU or CPU reference) while the
// frames of the previous batch are encoded and written on every core (issue: "writing uses both cores").
#include "dqskin/bake.hpp"

#include "bake_plan.hpp"
#include "bake_shares.hpp"
#include "bake_work.hpp"
#include "../base/byte_size.hpp"
#include "dqskin/error.hpp"
#include "dqskin/memory_ceiling.hpp"
#include "dqskin/frame_view.hpp"
#include "../write/glb_output.hpp"
#include "dqskin/deformer.hpp"
#include "../write/mesh_output.hpp"
#include "../job/job_run.hpp"
#include "../job/output_folder.hpp"
#include "../base/output_journal.hpp"
#include "../base/sha256.hpp"
#include "../texture/texture_output.hpp"
#include "manifest.hpp"
#include "motion_files.hpp"
#include "bones_bake.hpp"
#include "morph_bake.hpp"
#include "../write/glb_appearance.hpp"
#include "../texture/bone_profiles.hpp"
#include "vat_bake.hpp"
#include "vat_planner.hpp"
#include "../base/parallel_for.hpp"
#include "../kit/shader_kit.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <thread>
#include <tuple>

namespace dqskin {

using namespace bake_detail;

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

bool has(unsigned formats, BakeFormat f) { return formats & unsigned(f); }

// Whether the bake writes meshes beside textures (rest.glb and the profiles' meshes, bones_mesh.glb), which
// keep the source's materials and images.
bool has_look(unsigned formats) { return has(formats, BakeFormat::kVat) || has(formats, BakeFormat::kBones); }

// The planner's view of a bake: which inputs, clips, frames and shard.
PlanOptions plan_options(const BakeOptions& options) {
  PlanOptions plan = options.plan;
  // What the glb writer, the morph animation and the meshes beside textures copy from the file.
  plan.load.keep_source = has(options.formats, BakeFormat::kGlb) || has(options.formats, BakeFormat::kMorph) ||
                          has_look(options.formats);
  return plan;
}

// Thread-safe bookkeeping of one bake: outputs, stage times, progress.
struct Ledger {
  const BakeOptions& options;
  ProgressCounter& progress;
  BakeReport& report;
  std::mutex mutex;

  std::string absolute(const std::string& relative) const { return options.plan.out_dir + "/" + relative; }

  void check_cancel() const { check_cancelled(options.cancel); }

  void add_time(double BakeStageTimes::*stage, double seconds) {
    const std::lock_guard<std::mutex> lock(mutex);
    report.times.*stage += seconds;
  }

  void record(BakeOutput output) {
    const std::lock_guard<std::mutex> lock(mutex);
    report.outputs.push_back(std::move(output));
  }

  // Writes bytes we encoded: hashed from memory, no second read.
  void write(const std::string& relative, const std::string& bytes, OutputJournal& journal) {
    const Clock::time_point start = Clock::now();
    AtomicFile file(absolute(relative), false);  // synced all at once before the manifest
    file.write(bytes);
    const bool unchanged = file.commit({options.overwrite, &journal}) == Committed::kUnchanged;
    const std::string digest = sha256_hex(bytes);
    add_time(&BakeStageTimes::write, since(start));
    record({relative, bytes.size(), digest, unchanged});
  }

  // The same for a .glb in parts (a morph animation's): the head, the BIN chunk's bytes read back from
  // the temporary `spill` they went to, and the rest of the chunk; hashed as they are written.
  void write(const std::string& relative, const glb::GlbParts& glb, const AtomicFile& spill, OutputJournal& journal) {
    const Clock::time_point start = Clock::now();
    AtomicFile file(absolute(relative), false);
    Sha256 digest;
    auto put = [&](std::span<const char> bytes) {
      file.write(bytes);
      digest.add(bytes);
    };
    put(glb.head);
    std::unique_ptr<std::FILE, decltype(&std::fclose)> in(std::fopen(spill.temporary().c_str(), "rb"), &std::fclose);
    std::vector<char> chunk(size_t(4) << 20);
    uint64_t copied = 0;
    for (size_t n = 0; in && (n = std::fread(chunk.data(), 1, chunk.size(), in.get())) > 0; copied += n)
      put(std::span<const char>(chunk.data(), n));
    if (!in || std::ferror(in.get()) || copied != glb.spilled)
      throw OutputError(file.path() + ": its buffer could not be read back from " + spill.temporary());
    put(glb.bin);
    const bool unchanged = file.commit({options.overwrite, &journal}) == Committed::kUnchanged;
    add_time(&BakeStageTimes::write, since(start));
    record({relative, glb.size(), digest.hex(), unchanged});
  }

  // Records files another library wrote (OpenImageIO): hashed from disk.
  void record_files(const std::vector<std::string>& relative, const std::vector<Committed>& committed) {
    for (size_t i = 0; i < relative.size(); ++i) {
      const std::string path = absolute(relative[i]);
      record({relative[i], uint64_t(std::filesystem::file_size(path)), sha256_file(path),
              i < committed.size() && committed[i] == Committed::kUnchanged});
    }
  }

  void record_check(TextureCheck check) {
    const std::lock_guard<std::mutex> lock(mutex);
    report.checks.push_back(std::move(check));
  }

  void record_morph(MorphCheck check) {
    const std::lock_guard<std::mutex> lock(mutex);
    report.morphs.push_back(std::move(check));
  }

  // An input failed and its files were taken back: they leave the report (and so the manifest) too.
  void forget(const InputPlan& input) {
    const std::lock_guard<std::mutex> lock(mutex);
    const std::string prefix = input.stem + "/";
    std::erase_if(report.outputs, [&](const BakeOutput& o) { return o.path.rfind(prefix, 0) == 0; });
    std::erase_if(report.checks, [&](const TextureCheck& c) { return c.input == input.path; });
    std::erase_if(report.morphs, [&](const MorphCheck& c) { return c.input == input.path; });
  }
};

// Encoding buffers, taken by whichever thread encodes a frame and given back after the write, so that a
// buffer's pages are faulted in once per bake rather than once per frame.
class BufferPool {
public:
  std::string take() {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (free_.empty()) return {};
    std::string s = std::move(free_.back());
    free_.pop_back();
    return s;
  }
  void give(std::string s) {
    const std::lock_guard<std::mutex> lock(mutex_);
    free_.push_back(std::move(s));
  }

private:
  std::mutex mutex_;
  std::vector<std::string> free_;
};

// Bakes the clips of one input with one deformer.
class InputBaker {
public:
  // `glb`: the input's glb writer when glb is asked for; `appearance`: what the morph animation copies from
  // the file when morph is asked for; `look`: the source's materials and images for the meshes beside
  // textures when vat or bones is asked for (all made while planning the work). Warnings go to `warnings`.
  InputBaker(const InputPlan& input, const BakeOptions& options, GpuContext* context, Ledger& ledger,
             OutputJournal& journal, std::unique_ptr<GlbWriter> glb, std::unique_ptr<glb::Appearance> appearance,
             std::unique_ptr<glb::Appearance> look, std::vector<std::string>& warnings)
      : input_(input), asset_(*input.asset), options_(options), ledger_(ledger), journal_(journal),
        jobs_(options.jobs ? options.jobs : std::max(1u, std::thread::hardware_concurrency())), glb_(std::move(glb)),
        appearance_(std::move(appearance)), look_(std::move(look)), warnings_(warnings) {
    if (has(options.formats, BakeFormat::kPly) || has(options.formats, BakeFormat::kObj))
      mesh_ = std::make_unique<MeshFrameEncoder>(asset_, input.instances, asset_.materials.empty() ? "" : "materials.mtl");
    // Only when some frame is deformed (a bones-only bake needs no deformer, nor its texture size limit).
    // The decode-back check of bone textures deforms too.
    const bool checks_bones = has(options.formats, BakeFormat::kBones) && options.textures.check && !input.skins.empty() &&
                              std::any_of(input.clips.begin(), input.clips.end(), [](const ClipPlan& c) { return c.has_texture_frames(); });
    const bool deforms = checks_bones || std::any_of(input.clips.begin(), input.clips.end(), [&](const ClipPlan& c) {
                           return !frames_to_deform(c, options.formats).empty();
                         });
    if (deforms) {
      DeformerOptions o;
      o.mode = options.mode;
      o.backend = options.backend;
      o.gpu_memory = options.gpu_memory;
      o.threads = jobs_;
      o.before_batch = [this] { ledger_.check_cancel(); };
      deformer_ = make_deformer(context, asset_, input.instances, o);
    }
  }

  ~InputBaker() {
    if (deformer_) {
      ledger_.add_time(&BakeStageTimes::sample, deformer_->stats().sample_seconds);
      ledger_.add_time(&BakeStageTimes::deform, deformer_->stats().deform_seconds);
      ledger_.add_time(&BakeStageTimes::readback, deformer_->stats().readback_seconds);
    }
  }

  size_t bake_clip(const ClipPlan& clip) {
    ledger_.check_cancel();
    if (per_clip_formats(options_) == 0) return 0;  // only textures of every clip (--combine-clips): no folder
    journal_.make_folders(ledger_.absolute(clip.folder));
    if (clip.clip_mine) write_clip_files(clip);
    // The bone textures: their head writes them; each slice checks its frames.
    if (has(per_clip_formats(options_), BakeFormat::kBones) && !input_.skins.empty() && clip.has_texture_frames())
      write_bones(clip_texture_set(clip));

    const unsigned formats = per_clip_formats(options_);
    std::vector<size_t> frames = frames_to_deform(clip, formats);
    if (frames.empty()) return 0;
    const size_t counted = frames.size();  // what the progress counter expects of this clip
    std::unique_ptr<VatClipBake> vat;
    if (clip.has_texture_frames() && has(formats, BakeFormat::kVat)) {
      const Clock::time_point start = Clock::now();  // the texture's own passes: rest, planner, measuring
      vat = std::make_unique<VatClipBake>(*deformer_, input_, clip_texture_set(clip), options_, look_.get());
      ledger_.add_time(&BakeStageTimes::check, since(start));
    }
    // A texture of other frames than the bake's (the planner decimated them) deforms its own; the bake's
    // pass then needs only the per-frame outputs' frames.
    VatClipBake* shared = vat && vat->uses_bake_frames() ? vat.get() : nullptr;
    if (vat && !shared) {
      vat->encode_own_frames(*deformer_);
      frames = frames_to_deform(clip, formats & ~unsigned(BakeFormat::kVat));
      ledger_.progress.add(counted - frames.size(), input_.path, clip.name);
    }
    // The morph animation takes every frame of the bake's pass (frames_to_deform gives them all).
    std::unique_ptr<MorphClipBake> morph;
    if (clip.morph_mine && has(options_.formats, BakeFormat::kMorph)) morph = std::make_unique<MorphClipBake>(input_, clip, options_);
    std::vector<double> times;
    for (size_t f : frames) times.push_back(clip.times[f]);
    auto sink = [&](const DeformedBatch& batch) { encode_batch(batch, clip, frames, shared, morph.get()); };
    if (!times.empty()) deformer_->run(clip.clip, times, sink);
    if (morph) {
      const Clock::time_point start = Clock::now();
      MorphClipResult result = morph->finish(*appearance_, jobs_);
      ledger_.add_time(&BakeStageTimes::encode, since(start));
      ledger_.write(morph_file(clip), result.glb, *result.spill, journal_);
      result.spill.reset();  // its temporary goes
      ledger_.record_morph(std::move(result.check));
      for (std::string& w : result.warnings) warnings_.push_back(std::move(w));
    }
    if (vat) finish_vat(*vat);
    return counted;
  }

  // With --combine-clips: the textures of every clip of the input, after the clips' own passes, from
  // passes of their own (docs/DESIGN.md §4.9). Returns the frames deformed for them.
  size_t bake_combined(const TextureClips& set) {
    ledger_.check_cancel();
    if (!set.mine) return 0;
    journal_.make_folders(ledger_.absolute(set.folder));
    if (has(options_.formats, BakeFormat::kBones) && !input_.skins.empty()) write_bones(set);
    if (!has(options_.formats, BakeFormat::kVat)) return 0;
    Clock::time_point start = Clock::now();  // the texture's own passes: rest, planner, measuring
    VatClipBake vat(*deformer_, input_, set, options_, look_.get());
    ledger_.add_time(&BakeStageTimes::check, since(start));
    start = Clock::now();
    vat.encode_own_frames(*deformer_);
    ledger_.add_time(&BakeStageTimes::encode, since(start));
    ledger_.progress.add(set.frames(), input_.path, set.what);
    finish_vat(vat);
    return set.frames();
  }

private:
  // A texture's last rows, its decode-back check and its commit; its files and each clip's figures go into
  // the report.
  void finish_vat(VatClipBake& vat) {
    Clock::time_point start = Clock::now();
    vat.complete_images();  // the last rows; a PNG is compressed here, whole
    ledger_.add_time(&BakeStageTimes::encode, since(start));
    start = Clock::now();
    std::vector<std::string> names;
    std::vector<Committed> committed;
    for (auto& [name, c] : vat.finish(*deformer_, {options_.overwrite, &journal_})) {
      names.push_back(name);
      committed.push_back(c);
    }
    ledger_.add_time(&BakeStageTimes::check, since(start));
    ledger_.record_files(names, committed);
    for (size_t c = 0; c < vat.checks().size(); ++c) {
      TextureCheck check = bake_detail::texture_check(vat.checks()[c], input_.path, vat.clips().clips[c]->name, "vat");
      check.share = vat.share();
      ledger_.record_check(std::move(check));
    }
  }

  // The bone textures of a set of clips (texture/bones_bake.hpp).
  void write_bones(const TextureClips& set) {
    const Clock::time_point start = Clock::now();
    BonesClipResult bones =
        bake_bones_clip(deformer_.get(), input_, set, options_, {options_.overwrite, &journal_}, jobs_, look_.get());
    std::vector<std::string> names;
    std::vector<Committed> committed;
    for (auto& [name, c] : bones.files) {
      names.push_back(name);
      committed.push_back(c);
    }
    ledger_.record_files(names, committed);
    for (TextureCheck& check : bones.checks) ledger_.record_check(std::move(check));
    ledger_.add_time(options_.textures.check ? &BakeStageTimes::check : &BakeStageTimes::sample, since(start));
  }

  // Whole-animation files that need no deformation: the glb frames' shared images and the OBJ material
  // library.
  void write_clip_files(const ClipPlan& clip) {
    if (glb_)
      for (const GlbImageFile& image : glb_->image_files())
        ledger_.write(clip.folder + "/" + image.name, image.bytes, journal_);
    if (has(options_.formats, BakeFormat::kObj) && !asset_.materials.empty())
      ledger_.write(clip.folder + "/materials.mtl", encode_mtl(asset_), journal_);
  }

  // Encodes and writes the frames of one batch on all cores; the VAT rows go in order on one of them, the
  // morph animation's frames on another.
  void encode_batch(const DeformedBatch& batch, const ClipPlan& clip, const std::vector<size_t>& frames, VatClipBake* vat,
                    MorphClipBake* morph) {
    ledger_.check_cancel();
    const size_t tasks = batch.frame_count + (vat ? 1 : 0) + (morph ? 1 : 0);
    concurrency::parallel_for(tasks, jobs_, [&](size_t task) {
      ledger_.check_cancel();
      if (task >= batch.frame_count) {
        const Clock::time_point start = Clock::now();
        for (size_t k = 0; k < batch.frame_count; ++k) {
          if (task == batch.frame_count && vat) vat->append(frame_view(batch, k), frames[batch.first_frame + k]);
          else morph->append(frame_view(batch, k));
        }
        ledger_.add_time(&BakeStageTimes::encode, since(start));
        return;
      }
      const size_t f = frames[batch.first_frame + task];
      if (!clip.frame_mine[f]) return;
      encode_frame(frame_view(batch, task), clip, f);
    });
    ledger_.progress.add(batch.frame_count, input_.path, clip.name);
  }

  void encode_frame(const FrameView& view, const ClipPlan& clip, size_t f) {
    Clock::time_point start = Clock::now();
    if (glb_) {
      const std::string bytes = glb_->encode(view, clip.clip, clip.times[f]);
      ledger_.add_time(&BakeStageTimes::encode, since(start));
      ledger_.write(clip.frame_file(f, "glb"), bytes, journal_);
      start = Clock::now();
    }
    if (!mesh_) return;
    std::string bytes = buffers_.take();
    if (has(options_.formats, BakeFormat::kPly)) {
      mesh_->encode_ply(view, bytes);
      ledger_.add_time(&BakeStageTimes::encode, since(start));
      ledger_.write(clip.frame_file(f, "ply"), bytes, journal_);
      start = Clock::now();
    }
    if (has(options_.formats, BakeFormat::kObj)) {
      mesh_->encode_obj(view, bytes);
      ledger_.add_time(&BakeStageTimes::encode, since(start));
      ledger_.write(clip.frame_file(f, "obj"), bytes, journal_);
    }
    buffers_.give(std::move(bytes));
  }

  const InputPlan& input_;
  const Asset& asset_;
  const BakeOptions& options_;
  Ledger& ledger_;
  OutputJournal& journal_;
  const unsigned jobs_;
  std::unique_ptr<GlbWriter> glb_;
  std::unique_ptr<glb::Appearance> appearance_;  // when morph is asked for
  std::unique_ptr<glb::Appearance> look_;        // when vat or bones is asked for
  std::vector<std::string>& warnings_;
  std::unique_ptr<MeshFrameEncoder> mesh_;  // when PLY or OBJ is asked for
  BufferPool buffers_;
  std::unique_ptr<Deformer> deformer_;
};

}  // namespace

unsigned parse_bake_formats(const std::string& list) {
  unsigned formats = 0;
  size_t start = 0;
  while (start <= list.size()) {
    const size_t comma = std::min(list.find(',', start), list.size());
    const std::string name = list.substr(start, comma - start);
    static const std::pair<const char*, BakeFormat> known[] = {{"glb", BakeFormat::kGlb}, {"ply", BakeFormat::kPly},
                                                               {"obj", BakeFormat::kObj}, {"vat", BakeFormat::kVat},
                                                               {"bones", BakeFormat::kBones}, {"morph", BakeFormat::kMorph}};
    const auto it = std::find_if(std::begin(known), std::end(known), [&](const auto& k) { return name == k.first; });
    if (it == std::end(known)) throw InputError("--format '" + name + "' is not one of glb, ply, obj, vat, bones, morph");
    formats |= unsigned(it->second);
    start = comma + 1;
  }
  return formats;
}

bool BakeReport::any_failed() const {
  return std::any_of(inputs.begin(), inputs.end(), [](const InputResult& r) { return !r.error.empty(); });
}

BakeReport bake(const std::vector<std::string>& inputs, const BakeOptions& options,
                const std::function<void(const JobProgress&)>& progress) {
  const Clock::time_point start = Clock::now();
  OutputFolder out_folder(options.plan.out_dir, !options.dry_run);  // before any check, as the command always made it
  BakeReport report;
  if (options.plan.shard.count == 0 || options.plan.shard.index >= options.plan.shard.count) throw InputError("bad shard");
  if (!has_gpu_path(options.mode) && options.backend != Backend::kAuto && options.backend != Backend::kCpu)
    throw InputError("--mode " + std::string(to_string(options.mode)) +
                     " runs on the CPU reference only; use --backend cpu (or auto)");

  // Texture names are checked before any work.
  if (has(options.formats, BakeFormat::kVat) || has(options.formats, BakeFormat::kBones)) (void)vat_format(options.textures);
  if (BoneProfile p{}; has(options.formats, BakeFormat::kBones) && !parse_bone_profile(options.textures.bones_profile, p))
    throw InputError("--bones-profile '" + options.textures.bones_profile + "' is not one of dq, dq-cocos, mat3x4, mat4");
  if (has(options.formats, BakeFormat::kBones) && !options.textures.encoding.empty() &&
      options.textures.encoding != "float" && options.textures.encoding != "half" && !has(options.formats, BakeFormat::kVat))
    throw InputError("--encoding " + options.textures.encoding + " is for vertex-animation textures; bone textures are float or half");
  if (options.morph.quantize && !has(options.formats, BakeFormat::kMorph))
    throw InputError("--morph-quantize is for --format morph");
  if (options.textures.combine_clips) {
    // docs/DESIGN.md §4.9: which runtimes read several clips from one texture.
    if (!has(options.formats, BakeFormat::kVat) && !has(options.formats, BakeFormat::kBones))
      throw InputError("--combine-clips is for --format vat or bones");
    if (has(options.formats, BakeFormat::kVat) && vat_format(options.textures).profile == texture::VatProfile::kHoudini)
      throw InputError("--combine-clips: Houdini's VAT 3 shader plays one frame range per texture (its _data.json "
                       "holds one Frame Count); bake the houdini profile one texture per clip");
    if (BoneProfile p{}; has(options.formats, BakeFormat::kBones) &&
                         parse_bone_profile(options.textures.bones_profile, p) && p == BoneProfile::kDqCocos)
      throw InputError("--combine-clips: Cocos Creator's baked animation reads one joint texture per skeleton and "
                       "clip; bake the dq-cocos profile one texture per clip");
  }

  // The shader kits' files (docs/formats.md, "Shader kits"): once per bake, by its first shard.
  const std::vector<std::string> kits = kit::parse_shader_kits(options.shader_kit);  // checked on every shard
  const std::vector<kit::KitFile> kit_files =
      options.plan.shard.index == 0 ? kit::shader_kit_files(kits) : std::vector<kit::KitFile>{};

  std::vector<InputPlan> plans = plan_inputs(inputs, plan_options(options), report.times.load);
  deal_bake_shares(plans, options);
  for (const InputPlan& plan : plans) {
    for (const ClipPlan& clip : plan.clips) report.frames_total += frames_to_deform(clip, per_clip_formats(options)).size();
    if (options.textures.combine_clips && has(options.formats, BakeFormat::kVat))
      for (const TextureClips& set : texture_clip_sets(plan, true))
        if (set.mine) report.frames_total += set.frames();
  }

  // The work in numbers, before anything is written. The glb writers made for it (they measure a frame's
  // size) are the ones that bake.
  std::vector<std::unique_ptr<GlbWriter>> glb_writers(plans.size());
  std::vector<std::unique_ptr<glb::Appearance>> appearances(plans.size());
  std::vector<std::unique_ptr<glb::Appearance>> looks(plans.size());
  std::vector<MotionNodes> motion(plans.size());  // --sockets and --root-motion
  BakeWork work;
  for (size_t i = 0; i < plans.size(); ++i) {
    InputPlan& plan = plans[i];
    if (!plan.error.empty()) continue;
    // As an unskinned file's other formats are its rest pose or node animation, its bone textures are none:
    // a batch goes on, and the user is told why the folder has no bones_skinK files.
    if (has(options.formats, BakeFormat::kBones) && plan.skins.empty())
      plan.asset->warnings.push_back("the scene has no skinned mesh, so --format bones writes no bone texture for it");
    try {
      motion[i] = find_motion_nodes(plan, options.motion);  // before anything samples: the clips go in place
      set_in_place(plan, motion[i]);
      if (motion[i].root >= 0 && plan.asset->clips.empty())
        plan.asset->warnings.push_back("the file has no animation, so --root-motion in-place leaves its rest pose as it "
                                       "is and writes no root_motion.json");
      if (has(options.formats, BakeFormat::kGlb))
        glb_writers[i] = std::make_unique<GlbWriter>(*plan.asset, plan.instances, plan.scene, options.glb_images);
      if (has(options.formats, BakeFormat::kMorph))
        appearances[i] = std::make_unique<glb::Appearance>(glb::read_appearance(*plan.asset, plan.instances, plan.scene));
      if (has_look(options.formats)) looks[i] = std::make_unique<glb::Appearance>(glb::read_look(*plan.asset));
      plan.asset->source.reset();  // the writers have copied what they need: the JSON is not kept through the bake
      work += estimate_work(plan, options, glb_writers[i].get());
    } catch (const std::bad_alloc&) {
      plan.error = out_of_memory_message();
    } catch (const std::exception& e) {
      plan.error = e.what();
    }
  }
  report.vertex_frames = work.vertex_frames;
  report.planned_bytes = work.bytes;
  report.free_bytes = free_bytes(options.plan.out_dir);
  // Files already there are kept when they are equal; with --force the old ones stay (linked aside) until
  // their input has succeeded, so every new file needs its space.
  const bool keeps_existing = options.overwrite == Overwrite::kRefuseDifferent;
  const uint64_t needed = !keeps_existing ? work.bytes : work.bytes > work.existing ? work.bytes - work.existing : 0;
  if (needed > report.free_bytes)
    throw InputError(options.plan.out_dir + ": the bake would write up to " + byte_size(work.bytes) + " in " +
                     std::to_string(work.files) + " files, but the file system has " + byte_size(report.free_bytes) +
                     " free");

  if (options.dry_run) {
    for (InputPlan& plan : plans) {
      // With a texture budget, the planner's choices: it deforms each clip on the CPU.
      if (plan.error.empty() && has(options.formats, BakeFormat::kVat) && planner_active(options.textures)) {
        try {
          for (std::string& line : dry_run_plans(plan, options)) report.plans.push_back(std::move(line));
        } catch (const InputError& e) {
          plan.error = e.what();
        }
      }
      report.inputs.push_back({plan.path, plan.error, 0, plan.asset ? plan.asset->warnings : std::vector<std::string>{},
                               plan.asset ? plan.asset->notices : std::vector<std::string>{}});
      for (const ClipPlan& clip : plan.clips)
        for (std::string& file : planned_files(plan, clip, options)) report.outputs.push_back({std::move(file), 0, {}, false});
      for (const ClipPlan& clip : plan.clips)
        for (std::string& file : planned_motion_files(clip, motion[size_t(&plan - plans.data())]))
          report.outputs.push_back({std::move(file), 0, {}, false});
      if (options.textures.combine_clips && plan.error.empty())
        for (const TextureClips& set : texture_clip_sets(plan, true))
          for (std::string& file : planned_texture_files(plan, set, options)) report.outputs.push_back({std::move(file), 0, {}, false});
    }
    for (const kit::KitFile& file : kit_files) report.outputs.push_back({file.path, 0, {}, false});
    std::sort(report.outputs.begin(), report.outputs.end(), [](const auto& a, const auto& b) { return a.path < b.path; });
    report.wall_seconds = since(start);
    return report;
  }

  JobContext context(options.backend);
  ProgressCounter counter(report.frames_total, progress);
  Ledger ledger{options, counter, report, {}};
  report.inputs = for_each_input(
      plans,
      [&](const InputPlan& plan, OutputJournal& journal, InputResult& result) {
        const size_t i = size_t(&plan - plans.data());
        InputBaker baker(plan, options, context.for_deforming(options.mode), ledger, journal, std::move(glb_writers[i]),
                         std::move(appearances[i]), std::move(looks[i]), result.warnings);
        for (const ClipPlan& clip : plan.clips) {
          result.frames += baker.bake_clip(clip);
          // Sockets and root motion: whole-animation files, sampled on the CPU (docs/DESIGN.md §3.11).
          const Clock::time_point written = Clock::now();
          std::vector<std::string> names;
          std::vector<Committed> committed;
          for (auto& [name, c] : write_motion_files(plan, clip, motion[i], options, {options.overwrite, &journal}))
            names.push_back(std::move(name)), committed.push_back(c);
          ledger.record_files(names, committed);
          ledger.add_time(&BakeStageTimes::write, since(written));
        }
        if (options.textures.combine_clips)
          for (const TextureClips& set : texture_clip_sets(plan, true)) result.frames += baker.bake_combined(set);
      },
      [&](const InputPlan& plan) { ledger.forget(plan); });
  // What deformed: the GPU's context, or the CPU deformer (auto's choice is known once it was asked).
  const DeformPath path = deform_path(options.backend, options.mode, context.info() ? &context.get() : nullptr);
  if (path != DeformPath::kGpu) report.gpu = cpu_deformer_info(path);
  else if (context.info()) report.gpu = *context.info();
  if (!report.gpu.backend.empty()) report.deformer = describe(path);
  // The shader kits, when the bake has something to record (docs/formats.md, "Shader kits").
  if (!kit_files.empty() &&
      std::any_of(report.inputs.begin(), report.inputs.end(), [](const InputResult& r) { return r.error.empty(); })) {
    OutputJournal journal;
    for (const kit::KitFile& file : kit_files) {
      journal.make_folders(ledger.absolute(std::filesystem::path(file.path).parent_path().string()));
      ledger.write(file.path, std::string(file.bytes), journal);
    }
    journal.keep();
  }
  std::sort(report.outputs.begin(), report.outputs.end(), [](const auto& a, const auto& b) { return a.path < b.path; });
  std::sort(report.checks.begin(), report.checks.end(), [](const TextureCheck& a, const TextureCheck& b) {
    return std::tie(a.input, a.clip, a.texture) < std::tie(b.input, b.clip, b.texture);
  });
  std::sort(report.morphs.begin(), report.morphs.end(),
            [](const MorphCheck& a, const MorphCheck& b) { return std::tie(a.input, a.clip) < std::tie(b.input, b.clip); });
  if (!std::any_of(report.inputs.begin(), report.inputs.end(), [](const InputResult& r) { return r.error.empty(); })) {
    report.wall_seconds = since(start);
    return report;  // nothing baked, nothing to record
  }
  // One sync of the file system instead of one per file (milliseconds each): after a power loss, a manifest
  // that exists only lists outputs that are on disk.
  const Clock::time_point sync = Clock::now();
  std::filesystem::create_directories(options.plan.out_dir);
  sync_folder(options.plan.out_dir);
  report.times.write += since(sync);
  report.manifest = write_manifest(plans, options, report);
  out_folder.keep_if_any_succeeded(report.inputs);
  report.wall_seconds = since(start);
  return report;
}

}  // namespace dqskin
