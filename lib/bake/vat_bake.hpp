// One vertex-animation texture in a bake (internal to lib/bake), of one clip or, with --combine-clips, of
// every clip of an input one after another (docs/DESIGN.md §4.9): the passes around the writer.
// Before the bake's own pass over the frames, a rest pass (the mesh the offsets are taken from) and a
// measuring pass (the bounds the texels are remapped by, each frame's bounds for culling, whether the clip
// loops); during it, each frame is encoded and checked in memory against the frame it came from; after it,
// the decode-back check deforms the clip at the midpoints between frames and compares them with what the
// written files decode to, and proves by digest that the files hold the texels checked. The files are
// committed only when the check passes.
#pragma once

#include "bake_plan.hpp"
#include "../write/glb_appearance.hpp"
#include "../texture/vat_check.hpp"
#include "../texture/vat_writer.hpp"

#include "dqskin/deformer.hpp"
#include "../write/vertex_sharing.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace dqskin::bake_detail {

// The VAT format the options ask for. Throws InputError for unknown names and combinations the profile
// cannot write.
texture::VatFormat vat_format(const TextureOptions& options);

// The encoding of `clip`'s texture when shards may cut it into slices (texture::sliceable; no planner,
// which weighs every frame, and a layout the profile can hold); none otherwise.
std::optional<texture::VatEncoding> sliceable_vat(const InputPlan& input, const ClipPlan& clip, const TextureOptions& options);

// The VAT files of one texture, relative to the output folder, each with an upper bound of its size (images
// uncompressed). Throws InputError when the profile cannot hold the clip.
std::vector<std::pair<std::string, uint64_t>> planned_vat_files(const InputPlan& input, const TextureClips& set,
                                                               const TextureOptions& options);

class VatClipBake {
public:
  // Runs the rest and measuring passes with `deformer` and opens the files. Throws InputError when the
  // profile cannot hold the clip (size, format), OutputError when a file cannot be created. `look`: the
  // source's materials and images for the rest mesh (glb::read_look), or null.
  VatClipBake(Deformer& deformer, const InputPlan& input, TextureClips set, const BakeOptions& options,
              const glb::Appearance* look = nullptr);
  ~VatClipBake();

  // Whether the texture holds the bake's own frames (one clip at its times), so that the bake's pass feeds
  // it through append(); else (the planner decimated them, or several clips) encode_own_frames() deforms
  // its frames.
  bool uses_bake_frames() const;
  // The bake's pass: frame f of the clip, frames in order; a slice takes its own frames and its
  // neighbours (the clip's first frame, the frame after it) and ignores others.
  void append(const FrameView& frame, size_t f);
  void encode_own_frames(Deformer& deformer);
  // Frames the texture holds, over every clip.
  size_t frames() const;

  // Writes what the images still lack (the last rows, or a whole PNG) to their temporaries.
  void complete_images();
  // Completes the images if not done yet, runs the decode-back check (unless options.vat.check is off) and commits every
  // file. Throws InputError naming the clip when the decoded texture misses --max-error, decodes to one
  // pose while the clip moves, or holds a texel that is not finite; nothing is then left under a final
  // name. Returns the files' paths relative to the output folder with what happened to each.
  std::vector<std::pair<std::string, Committed>> finish(Deformer& deformer, const CommitOptions& commit);

  // The check's figures per clip (in the set's order), once finish() has run it.
  const std::vector<texture::DecodeCheck>& checks() const { return checks_; }
  // A slice's figures as a share for the merge (TextureCheck::share); empty for a whole texture.
  const std::string& share() const { return share_; }
  const TextureClips& clips() const { return set_; }

private:
  TextureClips set_;
  const BakeOptions& options_;
  std::vector<std::vector<double>> times_;  // per clip, the texture's frames
  SharedVertexLayout sharing_;  // the texture holds each distinct vertex once (vertex_sharing.hpp)
  std::unique_ptr<texture::VatWriter> writer_;
  std::vector<texture::DecodeCheck> checks_;
  std::string share_;
  bool complete_ = false;
};

}  // namespace dqskin::bake_detail
