// The decode-back check of a vertex-animation texture (internal to lib/texture and lib/bake): the images
// are read back from the files written, decoded on the CPU exactly as the profile's shader decodes them,
// and compared with the deformed meshes at every baked frame and at the midpoint between neighbours (the
// linear interpolation a runtime shows between frames).
#pragma once

#include "texel_image.hpp"
#include "vat_side_files.hpp"
#include "vat_writer.hpp"

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

private:
  static constexpr int kPerDecade = 200, kFirstDecade = -12, kDecades = 18;
  std::vector<size_t> bins_ = std::vector<size_t>(kPerDecade * kDecades + 2, 0);
  double max_ = 0;
  size_t count_ = 0;
};

class VatDecodeChecker {
public:
  // Reads the writer's images (temporaries) back. Throws OutputError when one cannot be read as written.
  explicit VatDecodeChecker(const VatWriter& writer);
  ~VatDecodeChecker();

  // The deformed mesh at baked frame f; frames come in order, each followed (but the last) by its
  // midpoint. The first frame given is the clip's first (of several in one texture, docs/DESIGN.md §4.9),
  // which the motion is measured from. Throws OutputError naming the file and texel when a texel is not finite.
  void baked_frame(size_t f, const FrameView& reference);
  // The deformed mesh halfway between frames f and f + 1.
  void midpoint(size_t f, const FrameView& reference);

  DecodeCheck result() const;
  // The distances behind result(), for figures over several clips.
  const ErrorHistogram& frame_errors() const { return frame_errors_; }
  const ErrorHistogram& midpoint_errors() const { return midpoint_errors_; }
  // How far the deformed meshes and the decoded ones move away from their first frame (largest vertex
  // distance over the clip): a texture whose frames all decode to one pose while the clip moves is a
  // failed bake.
  double reference_motion() const { return reference_motion_; }
  double decoded_motion() const { return decoded_motion_; }

private:
  struct Decoded {
    size_t frame = SIZE_MAX;
    std::vector<float> positions, normals;
  };
  const Decoded& decode(size_t f);
  void compare(const std::vector<float>& positions, const std::vector<float>& normals, const FrameView& reference,
               ErrorHistogram& errors, double& normal_degrees);

  void open_page(size_t page);

  const VatWriter& writer_;
  const VatEncoding& e_;
  size_t page_ = SIZE_MAX;  // the page the readers are open on
  std::string positions_name_, normals_name_;
  std::unique_ptr<TexelFileReader> positions_, normals_;
  TexelImage position_band_, normal_band_;
  bool whole_read_ = false;  // the bands hold rows read from the current page
  Decoded current_, next_;
  std::vector<float> first_positions_;
  ErrorHistogram frame_errors_, midpoint_errors_;
  double max_normal_degrees_ = 0, max_midpoint_normal_degrees_ = 0;
  double reference_motion_ = 0, decoded_motion_ = 0;
};

}  // namespace dqskin::texture
