// One clip's vertex-animation texture in any profile (internal to lib/texture and lib/bake): frames are
// encoded as they arrive, the images written to temporaries (streamed row band by row band for the
// frame-major layouts, whole for openvat's), then, after the decode-back check has read them, the side
// files and the rest mesh join them and all are committed at once.
#pragma once

#include "texel_image.hpp"
#include "vat_side_files.hpp"

#include "dqskin/atomic_file.hpp"
#include "dqskin/frame_view.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace dqskin::texture {

class VatFrameCheck;  // vat_check.hpp

// A shard's share of one texture (docs/DESIGN.md §6.5): frames [first, end) of a single clip, whose rows
// it encodes, checks and writes as pieces that `dqskin merge` splices into the images (exr_rows.hpp); the
// head writes the rest mesh and the side files as well (vat.json as a template, its decode_check filled in
// by the merge when the frames are checked). The whole texture by default.
struct VatSlice {
  size_t first = 0, end = 0;  // end 0: every frame
  bool head = true;
};

// Whether a texture can be cut into slices: frame-major rows in EXR files (PNG is one compressed stream).
bool sliceable(const VatEncoding& encoding);
// Whether a slice may start at frame f: at a page's first frame, or where a block of EXR rows starts.
bool slice_may_start(const VatEncoding& encoding, size_t f);
// The rows of `page` that frames [first, end) hold: the frames' own, and the padding rows below the page's
// last frame; empty ({0, 0}) when none of the frames is on the page.
TexelRows slice_page_rows(const VatLayout& layout, size_t first, size_t end, size_t page);
// A piece's file name: "<name>.rows-<first>-<end>" for rows [first, end) of the image `name`.
std::string piece_file_name(const std::string& name, size_t first_row, size_t end_row);
// The JSON template a head writes for the merge to fill: "<name>.template".
std::string template_file_name(const std::string& name);

class VatWriter {
public:
  // `folder`: the clip's output folder; `names`: the files in it (vat_file_names); `rest_glb`: the rest
  // mesh's bytes; `check`: check each frame in memory as it is encoded and keep the images' digests for
  // the read-back (vat_check.hpp; off for --no-check). Creates the images' temporaries now. Throws
  // OutputError naming a file that cannot be created, InputError for an image no file can hold.
  VatWriter(VatEncoding encoding, VatClipInfo info, const std::string& folder, VatFileNames names, std::string rest_glb,
            bool check = true, VatSlice slice = {});
  // Without commit(): nothing appears under the final names.
  ~VatWriter();
  VatWriter(const VatWriter&) = delete;
  VatWriter& operator=(const VatWriter&) = delete;

  // Encodes the next frame of the slice (frames come in order, each once) and, with `check`, compares its
  // texels with it. Throws as encode_vat_frame or VatFrameCheck::frame, or OutputError.
  void append(const FrameView& frame);
  // A slice's neighbours, encoded in memory for the check only (never written, no figures): the clip's
  // first frame, which motion is measured from, before a slice that starts later; the frame after the
  // slice, for the midpoint between it and the slice's last. Its texels are the next slice's, encoded by
  // the same function, which that shard's digest proves are the ones in its piece.
  void append_first(const FrameView& frame);
  void append_next(const FrameView& frame);
  const VatSlice& slice() const { return slice_; }
  // The rows of `page` this writer writes: [first, end); empty when the slice has no frame there.
  TexelRows page_rows(size_t page) const;
  // After the last frame: completes the images on disk (still under temporary names).
  void finish();

  const VatEncoding& encoding() const { return encoding_; }
  const Box& clip_bounds() const { return info_.clip_bounds; }
  // A page's images as written, for reading back: temporary path and final name (normals: empty when
  // none); only pages the slice has rows in.
  struct WrittenImage {
    std::string temporary, name;
  };
  WrittenImage positions(size_t page = 0) const;
  WrittenImage normals(size_t page = 0) const;
  // With `check`: the frames' figures, and each page's images' digests once finish() has run (the normal
  // image's: 0 when none).
  const VatFrameCheck* frame_check() const { return frame_check_.get(); }
  VatFrameCheck* frame_check() { return frame_check_.get(); }
  uint64_t position_digest(size_t page) const;
  uint64_t normal_digest(size_t page) const;

  // Writes dqskin's JSON (with `check`'s figures when given), the profile's side file and the rest mesh,
  // then commits every file: with kRefuseDifferent all are compared first, so a refusal changes none. A
  // slice commits its pieces, and when it is the head the other files, vat.json as a template when the
  // frames were checked (the merge adds the figures of every slice).
  // Returns the files' names relative to the folder and what happened to each, in the same order.
  // `clip_checks`: each clip's figures, for the clip table of a texture of several clips.
  std::vector<std::pair<std::string, Committed>> commit(const DecodeCheck* check, const CommitOptions& options,
                                                        std::vector<DecodeCheck> clip_checks = {});

private:
  struct Image;
  VatEncoding encoding_;
  VatClipInfo info_;
  std::string folder_;
  VatFileNames names_;
  std::string rest_glb_;
  VatSlice slice_;
  // One per page (null where the slice has no rows); normals_ empty without an image.
  std::vector<std::unique_ptr<Image>> positions_, normals_;
  std::unique_ptr<VatFrameCheck> frame_check_;
  size_t frames_written_ = 0;
  bool whole() const { return slice_.first == 0 && slice_.end == encoding_.layout.frames; }
  // Encodes frame f into bands of its own and hands them to the check as a neighbour of the slice.
  void encode_neighbour(const FrameView& frame, size_t f, bool first);
};

}  // namespace dqskin::texture
