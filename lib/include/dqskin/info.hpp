// Facts about an asset, as `dqskin info` prints them.
#pragma once

#include "dqskin/asset.hpp"

#include <string>
#include <vector>

namespace dqskin {

struct SkinnedMeshFacts {
  int node = -1, mesh = -1, skin = -1;
  std::string name;        // the node's name, else the mesh's
  size_t vertices = 0;     // over the mesh's primitives, each POSITION accessor counted once
  size_t triangles = 0;    // of the triangle-mode primitives
  int max_influences = 0;  // the most non-zero weights any vertex has
  int influence_sets = 0;  // JOINTS_n/WEIGHTS_n sets (1 or 2)
};

struct SkinFacts {
  std::string name;
  size_t joints = 0;
  bool non_rigid_in_bind_pose = false;  // a joint matrix with scale or shear beyond 1e-5 at rest
  bool non_rigid_in_animation = false;  // … at a key time of some clip
};

struct ClipFacts {
  std::string name;
  double duration = 0;   // the last key time (glTF time starts at 0)
  double first_key = 0;
  size_t channels = 0;
  std::vector<std::string> interpolations;  // distinct, sorted: "CUBICSPLINE", "LINEAR", "STEP"
};

struct MorphFacts {
  int mesh = -1;
  std::string name;
  size_t targets = 0;
};

struct AssetFacts {
  size_t scenes = 0;
  int default_scene = -1;
  size_t vertices = 0;          // every POSITION accessor counted once
  size_t joint_nodes = 0;       // distinct joint nodes over all skins
  std::vector<SkinnedMeshFacts> skinned_meshes;  // one per skinned mesh node
  std::vector<SkinFacts> skins;
  std::vector<ClipFacts> clips;
  std::vector<MorphFacts> morph_targets;  // meshes with morph targets
  std::vector<std::string> warnings;
  // Why the deforming commands refuse the file, though it is read (Asset::cannot_deform); empty when they
  // accept it.
  std::vector<std::string> cannot_deform;
};

AssetFacts describe(const Asset& asset);

}  // namespace dqskin
