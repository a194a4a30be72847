// The decode-back check of a vertex-animation texture (internal to lib/texture and lib/bake): the texels
// decoded on the CPU exactly as the profile's shader decodes them and compared with the deformed meshes
// at every baked frame (in memory, as the bake encodes them) and at the midpoint between neighbours (read
// back from the files written: the linear interpolation a runtime shows between frames), with a digest
// proving that the files decode to the texels compared.
#pragma once

#include "texel_image.hpp"
#include "vat_side_files.hpp"
#include "vat_writer.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace dqskin::texture {

// Distances whose 99th percentile is wanted without keeping them: a histogram of 200 bins per decade
// from 1e-12 to 1e6 (and one for exact zeros), so the percentile is known within 1.2 %, rounded up.
class ErrorHistogram {
public:
  void add(double error);
  void merge(const ErrorHistogram& other);
  double max() const { return max_; }
  size_t count() const { return count_; }
  // The smallest bin edge at or above the q-quantile (never above max()).
  double quantile(double q) const;
  // As a shard's manifest records it: {"max", "count", "bins": [[bin, count], ...]} (the bins not empty).
  nlohmann::json to_json() const;
  static ErrorHistogram from_json(const nlohmann::json& j, const std::string& what);

private:
  static constexpr int kPerDecade = 200, kFirstDecade = -12, kDecades = 18;
  std::vector<size_t> bins_ = std::vector<size_t>(kPerDecade * kDecades + 2, 0);
  double max_ = 0;
  size_t count_ = 0;
};

// The in-memory half of the check (docs/DESIGN.md §4.8): each frame as the bake's pass encodes it, its
// bands decoded as the shader decodes them and compared with the deformed frame it was encoded from (the
// bake's own frame, not a second deformation). The writer runs it; it keeps the figures and decoded
// frame 0, never a frame's texels.
class VatFrameCheck {
public:
  explicit VatFrameCheck(const VatEncoding& e) : e_(e), clips_(1) {}
  // A texture of several clips: each clip's first frame, in increasing order from
  // 0; each clip has its own figures and its motion is measured from its own first frame. Before the
  // first frame; one clip from frame 0 when not called.
  void set_clip_starts(std::vector<size_t> first_frames);
  // Frame f in `positions` (and `normals`, the normal image's band, when there is one), bands holding its
  // rows; `reference` the frame it was encoded from. Frames come in order, each once. Throws OutputError
  // naming the file (`positions_name`, `normals_name`) and texel when a texel is not finite.
  void frame(size_t f, const TexelImage& positions, const TexelImage* normals, const FrameView& reference,
             const std::string& positions_name, const std::string& normals_name);
  // A slice's neighbours (VatWriter::append_first, append_next), decoded, never compared: the clip's first
  // frame (one clip), which a later slice measures motion from; the frame after the slice, for the last
  // midpoint.
  void first_frame(const TexelImage& positions, const TexelImage* normals);
  void next_frame(size_t f, const TexelImage& positions, const TexelImage* normals);
  struct Decoded {
    size_t frame = SIZE_MAX;
    std::vector<float> positions, normals;
  };
  const Decoded& next() const { return next_; }

  struct Clip {
    size_t first_frame = 0;
    ErrorHistogram errors;
    double min_cosine = 1;  // of the angles between decoded and reference normals
    double reference_motion = 0, decoded_motion = 0;
    std::vector<float> first_positions;  // the clip's first frame decoded (3 floats per vertex)
  };
  size_t clips() const { return clips_.size(); }
  size_t clip_of(size_t f) const;
  const Clip& clip(size_t c) const { return clips_[c]; }

private:
  const VatEncoding& e_;
  std::vector<Clip> clips_;
  std::vector<float> positions_, normals_;
  Decoded next_;
};

// A slice's figures in a form that adds up over slices (`dqskin merge`): the histograms and the largest
// angles. The whole texture's figures are those of the sum.
struct DecodeShare {
  ErrorHistogram frames, midpoints;
  double max_normal_degrees = 0, max_midpoint_normal_degrees = 0;
  void merge(const DecodeShare& other);
  DecodeCheck figures() const;
  nlohmann::json to_json() const;
  // Throws InputError naming `what` when `j` is not one.
  static DecodeShare from_json(const nlohmann::json& j, const std::string& what);
};

// The read-back half (docs/DESIGN.md §4.8): reads the images back from the files written, proves that
// every texel decoded equals the one the writer's VatFrameCheck compared (a digest of each image's rows,
// taken as the writer handed them to the file), and compares the midpoints between frames, decoded from
// the file, with the clip deformed there (a deformation of its own, which the bake's pass did not make).
class VatDecodeChecker {
public:
  // Reads the writer's images (temporaries) back; the writer must have checked its frames
  // (VatWriter::frame_check). Throws OutputError when an image cannot be read as written.
  explicit VatDecodeChecker(const VatWriter& writer);
  ~VatDecodeChecker();

  // The deformed mesh halfway between frames f and f + 1; midpoints come in order.
  void midpoint(size_t f, const FrameView& reference);
  // Reads what the midpoints did not, compares every image's digest with the writer's and returns the
  // figures of frames and midpoints over every clip. Throws OutputError naming the file when its texels
  // differ from those the writer checked.
  DecodeCheck finish();
  // Clip c's figures (VatFrameCheck::set_clip_starts), once finish() has run.
  DecodeCheck clip_result(size_t c) const;
  // The figures as a share that adds up over slices (one clip), once finish() has run.
  DecodeShare share() const;

  // How far clip c's deformed meshes and decoded ones move away from its first frame decoded (largest
  // vertex distance over the clip, frames and midpoints): a texture whose frames all decode to one pose
  // while the clip moves is a failed bake. The midpoints, deformed apart from the bake's pass, see a
  // texture stuck in one pose even when the frames fed to the writer were.
  double reference_motion(size_t c = 0) const;
  double decoded_motion(size_t c = 0) const;

private:
  using Decoded = VatFrameCheck::Decoded;
  const Decoded& decode(size_t f);
  void open_page(size_t page);
  // Reads rows [first, first + count) of the current page into the bands, digesting those not yet
  // digested (rows are read in order).
  void read_rows(size_t first, size_t count);
  // Reads and digests the current page's remaining rows and compares the digests with the writer's.
  void finish_page();

  const VatWriter& writer_;
  const VatEncoding& e_;
  const VatFrameCheck& frames_;
  size_t page_ = SIZE_MAX;  // the page the readers are open on
  TexelRows rows_;          // the rows of that page the writer wrote
  std::string positions_name_, normals_name_;
  std::unique_ptr<TexelFileReader> positions_, normals_;
  TexelImage position_band_, normal_band_;
  bool band_read_ = false;  // the bands hold rows read from the current page
  size_t digested_rows_ = 0;  // of the current page
  TexelDigest position_digest_, normal_digest_;
  std::vector<bool> pages_verified_;
  Decoded current_, next_;
  struct Midpoints {
    ErrorHistogram errors;
    double min_cosine = 1, reference_motion = 0;
  };
  std::vector<Midpoints> midpoints_;  // per clip
};

}  // namespace dqskin::texture
