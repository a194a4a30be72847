// Texture outputs of `dqskin bake` (shared/DESIGN.md "DeformedFrames ──write──▶ vertex-animation textures,
// bone textures"): vertex-animation textures (VAT) streamed frame by frame, and the BoneTexture the
// compute shader reads. Both are RGBA32F OpenEXR images with a JSON side file; the layouts are DESIGN.md's
// "Vertex-animation texture (VAT) layout" and "BoneTexture layout". OpenImageIO stays out of this header.
#pragma once

#include "dqskin/atomic_file.hpp"
#include "dqskin/bone_texture.hpp"
#include "dqskin/frame_view.hpp"

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace dqskin {

// The widest a VAT row gets (DESIGN.md "at most 8192 texels"): larger vertex counts wrap onto several rows
// per frame, so the texture stays within the size limits of the GPUs that sample it.
inline constexpr size_t kVatMaxWidth = 8192;

// One mesh primitive whose vertices a VAT holds, in the order the texture holds them.
struct VatSource {
  int node = -1;
  int mesh = -1;
  int primitive = -1;  // index in the mesh's primitives
  size_t vertices = 0;
  std::string node_name, mesh_name;
};

// The primitives of `instances` in the order deform_frame and frame_view give them: instances in order,
// each instance's primitives in mesh order.
std::vector<VatSource> vat_sources(const Asset& asset, const std::vector<MeshInstance>& instances);

// Streams the vertex-animation textures of one clip: one RGBA32F EXR for positions (xyz, w = 1), one for
// normals (xyz, w = 0; zeros for primitives without normals), and the JSON side file. Frames arrive in
// order and are encoded as they arrive, so memory holds one frame, not the clip.
//
// Layout: with W = min(vertex count, wrap) and R = ⌈vertex count / W⌉ rows per frame, vertex v of frame f
// is texel (v % W, f·R + v / W); the image is W × (frames·R); texels past the last vertex of a frame are 0.
class VatWriter {
public:
  // positions_path and normals_path name the .exr files, json_path the side file (it names the two images
  // relative to its own folder). `times` holds every frame's time in seconds (at least one frame); `fps` is
  // 0 when the times are not a grid (keys or explicit times; the JSON then says null). `wrap` is the widest
  // row (tests use small values to exercise wrapping). Creates the temporaries now: throws OutputError
  // naming the file when one cannot be created, InputError when there is no vertex or no frame
  // or the image would be too large for EXR.
  VatWriter(std::string positions_path, std::string normals_path, std::string json_path,
            std::vector<VatSource> sources, std::vector<double> times, double fps, std::string clip_name,
            size_t wrap = kVatMaxWidth);
  // Without commit(): nothing appears under the final names (the temporaries are removed).
  ~VatWriter();
  VatWriter(const VatWriter&) = delete;
  VatWriter& operator=(const VatWriter&) = delete;

  // Encodes the next frame. Its primitives must match the sources (count and vertex counts), and at most
  // times.size() frames may be appended. Throws OutputError naming the file when writing fails.
  void append(const FrameView& frame);

  // After every frame: finishes both images, writes the JSON and commits the three files with `overwrite`,
  // images first, so the JSON appears only beside complete images. With kRefuseDifferent every file is
  // compared before any is renamed, so a refusal changes none of them. Returns what happened to
  // positions, normals and JSON, in that order. Throws std::logic_error when frames are missing,
  // OutputError naming the file otherwise.
  std::vector<Committed> commit(const CommitOptions& options);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Writes the BoneTexture of skin `skin` exactly as the shader reads it: an RGBA32F EXR of joints·T × frames
// texels holding texture.rgba bit for bit, and a JSON side file naming the skin, its joint names in order,
// T, the frame count, frame times (`times`, one per frame) and fps (0: not a grid, the JSON says null).
// Commits both files with `overwrite` (image first; with kRefuseDifferent both are compared before either
// is renamed) and returns what happened to each, image then JSON. Throws OutputError naming the file.
std::vector<Committed> write_bone_texture(const std::string& exr_path, const std::string& json_path,
                                          const BoneTexture& texture, const Asset& asset, int skin,
                                          std::span<const double> times, double fps, const CommitOptions& options);

}  // namespace dqskin
