// One skin's bone texture in any profile (internal to lib/texture and lib/bake): the image written to a
// temporary at once (EXR, float32 or half), readable back as its shader will see it for the decode-back
// check, and committed with its JSON side file afterwards.
#pragma once

#include "bone_profiles.hpp"
#include "texel_encoding.hpp"
#include "vat_side_files.hpp"

#include "dqskin/asset.hpp"
#include "dqskin/atomic_file.hpp"

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace dqskin::texture {

class BoneTextureWriter {
public:
  // Writes `image` (of `asset`'s skin `skin`, one row of frames per `times`) as `type` (float or half)
  // into exr_path's temporary, with `compression` (texel_image.hpp exr_compression). Throws InputError for an empty image or a value half cannot hold (naming
  // the file and texel), OutputError when the file cannot be written.
  BoneTextureWriter(const std::string& exr_path, const std::string& json_path, BoneImage image, TexelType type,
                    const Asset& asset, int skin, std::span<const double> times, double fps,
                    const std::string& compression = "");
  ~BoneTextureWriter();
  BoneTextureWriter(const BoneTextureWriter&) = delete;
  BoneTextureWriter& operator=(const BoneTextureWriter&) = delete;

  // The texture read back from the written file, as the shader receives it (half values widened).
  BoneImage read_back() const;

  // Writes the JSON side file (with `check`'s figures when given) and commits image and JSON, image first;
  // with kRefuseDifferent both are compared before either is renamed. Returns what happened to each.
  // `clips`: the clip table (none when empty); `clip_checks`: with several clips, each
  // clip's figures (docs/DESIGN.md §4.9).
  std::vector<Committed> commit(const DecodeCheck* check, const CommitOptions& options,
                                const std::vector<VatClipEntry>& clips = {},
                                const std::vector<DecodeCheck>& clip_checks = {});

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dqskin::texture
