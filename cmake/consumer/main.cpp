// Loads the glTF file named on the command line through an installed dqskin and prints what it holds
// and the first vertex of the rest pose, deformed on the CPU. Exit status 1 on any error.
#include <dqskin/load.hpp>
#include <dqskin/skinning.hpp>
#include <dqskin/version.hpp>

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s FILE.gltf|FILE.glb\n", argv[0]);
    return 1;
  }
  try {
    const dqskin::Asset asset = dqskin::load_asset(argv[1]);
    const auto instances = dqskin::mesh_instances(asset, dqskin::choose_scene(asset, -1));
    const dqskin::Pose rest = dqskin::sample_pose(asset, nullptr, 0.0);
    const dqskin::DeformedFrame frame = dqskin::deform_frame(asset, instances, rest, dqskin::BlendMode::kDqs);
    size_t vertices = 0;
    for (const auto& primitive : frame.primitives) vertices += primitive.positions.size();
    std::printf("dqskin %s: skins %zu nodes %zu clips %zu vertices %zu\n", dqskin::kVersion, asset.skins.size(),
                asset.nodes.size(), asset.clips.size(), vertices);
    for (const auto& primitive : frame.primitives) {
      if (primitive.positions.empty()) continue;
      const auto& p = primitive.positions.front();
      std::printf("rest vertex 0: %.6f %.6f %.6f\n", p.x, p.y, p.z);
      break;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dqskin_consumer: %s\n", e.what());
    return 1;
  }
  return 0;
}
