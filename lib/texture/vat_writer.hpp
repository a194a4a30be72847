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

class VatWriter {
public:
  // `folder`: the clip's output folder; `names`: the files in it (vat_file_names); `rest_glb`: the rest
  // mesh's bytes; `check`: check each frame in memory as it is encoded and keep the images' digests for
  // the read-back (vat_check.hpp; off for --no-check). Creates the images' temporaries now. Throws
  // OutputError naming a file that cannot be created, InputError for an image no file can hold.
  VatWriter(VatEncoding encoding, VatClipInfo info, const std::string& folder, VatFileNames names, std::string rest_glb,
            bool check = true);
  // Without commit(): nothing appears under the final names.
  ~VatWriter();
  VatWriter(const VatWriter&) = delete;
  VatWriter& operator=(const VatWriter&) = delete;

  // Encodes the next frame (frames come in order, each once) and, with `check`, compares its texels with
  // it. Throws as encode_vat_frame or VatFrameCheck::frame, or OutputError.
  void append(const FrameView& frame);
  // After the last frame: completes the images on disk (still under temporary names).
  void finish();

  const VatEncoding& encoding() const { return encoding_; }
  const Box& clip_bounds() const { return info_.clip_bounds; }
  // A page's images as written, for reading back: temporary path and final name (normals: empty when
  // none).
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
  // then commits every file: with kRefuseDifferent all are compared first, so a refusal changes none.
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
  std::vector<std::unique_ptr<Image>> positions_, normals_;  // one per page; normals_ empty without an image
  std::unique_ptr<VatFrameCheck> frame_check_;
  size_t frames_written_ = 0;
};

}  // namespace dqskin::texture
