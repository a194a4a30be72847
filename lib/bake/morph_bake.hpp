// One clip's morph-target animation in a bake (internal to lib/bake): the bake's pass hands every frame of
// the clip in order; finish() chooses the keys (every frame, or under --max-error the fewest that keyframe
// reduction needs), encodes animation.glb (write/morph_glb.hpp), and measures what it decodes to at every
// baked frame, interpolated between keys as a viewer does, against the deformed frames.
#pragma once

#include "bake_plan.hpp"
#include "../write/glb_appearance.hpp"

#include "dqskin/atomic_file.hpp"
#include "dqskin/frame_view.hpp"
#include "../write/vertex_sharing.hpp"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace dqskin::bake_detail {

// <clip folder>/animation.glb, relative to the output folder.
std::string morph_file(const ClipPlan& clip);

// What the animation holds while its keys are chosen: every frame's positions and normals, 24 bytes a
// distinct vertex.
uint64_t morph_frames_bytes(const InputPlan& input, const ClipPlan& clip);

// An upper bound of the file's size (every frame a dense float target), for the planned bytes.
uint64_t planned_morph_bytes(const InputPlan& input, const ClipPlan& clip);

// The documented limits of WebGL2 viewers that a morph-target animation of `targets` targets exceeds, one
// line each starting with `what`: past 200 targets, and a primitive whose vertices (each one texel, two
// with normals) overflow the 2048 × 2048 texels a morph-target texture is sure to hold. `primitives`:
// each primitive's vertex count and whether its normals are morphed.
std::vector<std::string> morph_viewer_warnings(const std::string& what, size_t targets,
                                               const std::vector<std::pair<size_t, bool>>& primitives);

struct MorphClipResult {
  // The .glb: the BIN chunk's bytes (glb.spilled of them, its padding included) went to `spill` (a
  // temporary beside the file, never committed) as they were made, so that memory holds the frames and
  // not a second copy of them.
  glb::GlbParts glb;
  std::unique_ptr<AtomicFile> spill;
  MorphCheck check;
  std::vector<std::string> warnings;  // viewer limits the file exceeds
};

class MorphClipBake {
public:
  // Throws InputError when the clip cannot be a glTF animation (frame times not increasing) or has no
  // vertices.
  MorphClipBake(const InputPlan& input, const ClipPlan& clip, const BakeOptions& options);

  // The bake's pass: every frame of the clip, in order.
  void append(const FrameView& frame);

  // Chooses the keys, encodes and measures, on `threads` threads. Throws InputError naming the clip when
  // the measured error exceeds --max-error, or when the quantization grid alone cannot meet it (then
  // before encoding). Once: the frames that are not keys are freed before encoding.
  MorphClipResult finish(const glb::Appearance& appearance, unsigned threads);

private:
  const InputPlan& input_;
  const ClipPlan& clip_;
  const BakeOptions& options_;
  std::string what_;  // "clip <name>" for messages
  size_t vertices_ = 0;
  SharedVertexLayout sharing_;       // the keys hold each distinct vertex once (vertex_sharing.hpp)
  std::vector<size_t> first_;        // per primitive that writes vertices: its first vertex
  std::vector<bool> with_normals_;   // per primitive that writes vertices: NORMAL written (the source has normals)
  std::vector<std::vector<float>> positions_, normals_;  // per frame: 3 per vertex, every primitive
};

}  // namespace dqskin::bake_detail
