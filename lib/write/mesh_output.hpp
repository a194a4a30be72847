// One frame's deformed meshes as one mesh, and its PLY and OBJ files (docs/DESIGN.md §2.5): every
// primitive of every instance merged in scene order, vertices in glTF accessor order, each distinct vertex
// once per instance (primitives that share vertex data add faces only: vertex_sharing.hpp gives the
// order), faces from the triangle-mode primitives (strips and fans are turned into lists; points and lines
// have no faces).
#pragma once

#include "dqskin/frame_view.hpp"
#include "vertex_sharing.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace dqskin {

struct MergedMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // zero for vertices of primitives that have none
  std::vector<glm::vec2> uv0;      // glTF convention (origin top left); zero where a primitive has none
  std::vector<uint32_t> triangles; // three indices per face, into the merged vertices

  // One per primitive, in order: its faces and where they came from (OBJ objects and materials).
  struct Group {
    std::string node_name;
    int material = -1;  // index into Asset::materials, or -1
    size_t first_triangle = 0, triangle_count = 0;
  };
  std::vector<Group> groups;
};

// What every frame of `instances` shares: texture coordinates, faces and groups (no positions, normals).
MergedMesh merge_topology(const Asset& asset, const std::vector<MeshInstance>& instances);
// Merges one frame (as deform_frame orders primitives: instances, then their mesh's primitives).
MergedMesh merge_frame(const Asset& asset, const std::vector<MeshInstance>& instances, const FrameView& frame);

// Binary little-endian PLY: x y z nx ny nz s t per vertex, faces as uchar-counted uint lists.
std::string encode_ply(const MergedMesh& mesh);

// Wavefront OBJ with v, vt (t flipped to OBJ's bottom-left origin), vn, one object per primitive named
// after its node, and `usemtl` per primitive when `mtl_file` is not empty (then `mtllib mtl_file`).
// Numbers are written in their shortest round-trip form, so reading them back gives the same floats.
std::string encode_obj(const MergedMesh& mesh, const Asset& asset, const std::string& mtl_file);

// The frames of one input as PLY and OBJ, byte for byte what encode_ply and encode_obj write for
// merge_frame, made for baking many frames: what every frame shares (the header, texture coordinates and
// faces, encoded once here) is copied, and only positions and normals are encoded per frame. Thread-safe
// after construction.
class MeshFrameEncoder {
public:
  MeshFrameEncoder(const Asset& asset, const std::vector<MeshInstance>& instances, const std::string& mtl_file);
  // Replaces `out` with the frame's file (its capacity is reused: pass the same string frame after frame).
  void encode_ply(const FrameView& frame, std::string& out) const;
  void encode_obj(const FrameView& frame, std::string& out) const;
  // Bytes of every frame's PLY file (they all have the same size).
  size_t ply_size() const { return ply_header_.size() + vertices_ * kPlyVertexBytes + ply_faces_.size(); }

private:
  static constexpr size_t kPlyVertexBytes = 32;  // x y z nx ny nz s t
  MergedMesh shared_;  // merge_topology(): its texture coordinates (its faces are kept encoded below)
  SharedVertexLayout layout_;  // which primitives of a frame write vertices
  size_t vertices_ = 0;
  std::string ply_header_, ply_faces_;
  std::string obj_header_, obj_texcoords_, obj_faces_;
};

// The material library for encode_obj: Kd and d from each material's base color factor. Empty when the
// asset has no materials (then OBJ files name no library).
std::string encode_mtl(const Asset& asset);

// The name encode_obj/encode_mtl use for a material: its glTF name with blanks replaced (OBJ names are
// single words), or material_<index> when it has none or shares it with an earlier one; -1 is the
// default material.
std::string obj_material_name(const Asset& asset, int material);

}  // namespace dqskin
