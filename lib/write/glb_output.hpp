// One baked frame as a static glTF 2.0 binary (docs/DESIGN.md §1.1, write): every
// deformed mesh instance, the scene's node hierarchy at the frame's time, and the source's appearance
// (materials, textures, samplers, images, cameras, lights, UVs, colours). Skins, animations and morph
// targets are removed: the file shows the frame as it is, in any viewer, without dqskin.
#pragma once

#include "dqskin/animation.hpp"
#include "dqskin/frame_view.hpp"
#include "dqskin/glb_images.hpp"
#include "dqskin/skinning.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace dqskin {

// An image written once beside the frames (GlbImages::kShared): `name` is the URI the frames use, relative
// to their folder.
struct GlbImageFile {
  std::string name;
  std::string bytes;
};

// Encodes frames of one asset as .glb bytes. What does not change from frame to frame (appearance, images,
// texture coordinates, colours, indices) is prepared once by the constructor; encode() adds the frame's
// node transforms and vertex positions, normals and tangents.
//
// The output has mesh i for instance i (a new mesh per instance: one mesh drawn by two nodes deforms
// differently), drawn by the instance's node with its vertices in that node's local space. A node whose
// world matrix is singular at a frame cannot carry them: it keeps no mesh there, and a new root node
// "<name> (deformed)" with the identity transform draws the world-space vertices.
class GlbWriter {
public:
  // `asset` must outlive the writer and be loaded with LoadOptions::keep_source (Asset::source holds the
  // appearance objects and attributes that the rest of the Asset does not keep; std::invalid_argument
  // without it). `instances` = mesh_instances(asset, scene), the order of the FrameView primitives;
  // `scene` = choose_scene(...), -1 when the file has no scenes (then one scene of every root node is
  // written). `images`: where the images go. Throws InputError when an attribute the frames copy
  // (TEXCOORD_n, COLOR_n) is malformed.
  GlbWriter(const Asset& asset, std::vector<MeshInstance> instances, int scene, GlbImages images = GlbImages::kEmbed);
  ~GlbWriter();
  GlbWriter(GlbWriter&&) noexcept;
  GlbWriter& operator=(GlbWriter&&) noexcept;

  // The .glb bytes of one frame: `frame` holds its deformed world-space vertices (one PrimitiveView per
  // primitive of every instance, as deform_frame orders them), `clip` (null: rest pose) at `time` gives
  // the nodes' transforms. Byte-identical for equal inputs. Const and safe to call from several threads
  // at once. Non-unit or non-finite normals and tangents are replaced (by the rest ones, or +z and +x) so
  // that the file stays valid; a non-finite position throws std::invalid_argument, as does a frame whose
  // primitives do not match the instances.
  std::string encode(const FrameView& frame, const Clip* clip, double time) const;

  // With GlbImages::kShared, the image files the frames reference, which the caller writes into the frames'
  // folder; else none.
  const std::vector<GlbImageFile>& image_files() const;

private:
  struct Impl;
  std::unique_ptr<const Impl> impl_;
};

}  // namespace dqskin
