#include "memory_estimate.hpp"

#include "dqskin/asset.hpp"
#include "draco.hpp"
#include "image_size.hpp"
#include "../base/saturating.hpp"

#include <algorithm>

namespace dqskin::gltf {
namespace {

using saturating::add;
using saturating::mul;

// Values (count × components) of accessor `index`; 0 when it does not exist (the loader reports that).
uint64_t values(const tinygltf::Model& model, int index) {
  if (index < 0 || size_t(index) >= model.accessors.size()) return 0;
  const tinygltf::Accessor& a = model.accessors[size_t(index)];
  const int components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
  return components > 0 ? mul(a.count, uint64_t(components)) : 0;
}

int find(const std::map<std::string, int>& attributes, const std::string& name) {
  const auto it = attributes.find(name);
  return it == attributes.end() ? -1 : it->second;
}

class Tally {
public:
  explicit Tally(const tinygltf::Model& model) : model_(model) {}

  // One read of an accessor: decoded to double, then float (accessor.cpp), then kept as `kept_bytes` per
  // value in the Asset.
  uint64_t read(int accessor, uint64_t kept_bytes) {
    const uint64_t n = values(model_, accessor);
    ++e.accessor_uses;
    e.transient = std::max(e.transient, mul(n, 8 + 4));
    e.asset = add(e.asset, mul(n, kept_bytes));
    return n;
  }

  void primitive(const tinygltf::Primitive& p, bool kept_source) {
    const int position = find(p.attributes, "POSITION");
    const uint64_t vertices = position >= 0 && size_t(position) < model_.accessors.size() ? model_.accessors[size_t(position)].count : 0;
    read(position, 4);
    if (const int a = find(p.attributes, "NORMAL"); a >= 0) {
      read(a, 4);
    } else {  // smooth_normals: float normals kept, double sums and the triangle list while computing them
      e.asset = add(e.asset, mul(vertices, 12));
      const uint64_t corners = p.indices >= 0 ? values(model_, p.indices) : vertices;
      e.transient = std::max(e.transient, add(mul(vertices, 24), mul(corners, 3 * 4)));
    }
    for (const char* name : {"TANGENT", "TEXCOORD_0", "TEXCOORD_1"})
      if (const int a = find(p.attributes, name); a >= 0) read(a, 4);
    if (const int a = find(p.attributes, "COLOR_0"); a >= 0) read(a, 6);  // RGB is widened to RGBA
    if (p.indices >= 0) read(p.indices, 4);
    // Every influence set the loader reads: joints as uint16, weights as float, all sets merged in a copy.
    for (int set = 0; set < kMaxInfluenceSets; ++set) {
      if (const int a = find(p.attributes, "JOINTS_" + std::to_string(set)); a >= 0) read(a, 2 * 2);
      if (const int a = find(p.attributes, "WEIGHTS_" + std::to_string(set)); a >= 0) read(a, 4 * 2);
    }
    for (const auto& target : p.targets)
      for (const auto& [name, accessor] : target)
        if (name == "POSITION" || name == "NORMAL" || name == "TANGENT") read(accessor, 4);
    if (kept_source)  // keep_source: every TEXCOORD_n and COLOR_n decoded once more, as float
      for (const auto& [name, accessor] : p.attributes)
        if (name.rfind("TEXCOORD_", 0) == 0 || name.rfind("COLOR_", 0) == 0) read(accessor, 4);
  }

  MemoryEstimate finish() {
    for (const tinygltf::Buffer& b : model_.buffers) e.file = add(e.file, b.data.size());
    // Decoded views are buffers of their own by now (decode_meshopt); named apart, not counted twice.
    for (const tinygltf::BufferView& v : model_.bufferViews)
      if (v.extensions.count("EXT_meshopt_compression")) e.decoded = add(e.decoded, v.byteLength);
    e.file = e.file > e.decoded ? e.file - e.decoded : 0;
    const DracoEstimate draco = estimate_draco(model_);  // accessors written from KHR_draco_mesh_compression
    e.decoded = add(e.decoded, draco.decoded);
    e.transient = std::max(e.transient, draco.transient);
    for (const tinygltf::Image& i : model_.images) {
      e.file = add(e.file, i.image.size());
      e.asset = add(e.asset, i.image.size());  // EncodedImage keeps a copy
    }
    e.asset = add(e.asset, mul(model_.nodes.size(), sizeof(Node) + sizeof(Mat4<double>)));
    return e;
  }

  MemoryEstimate e;

private:
  const tinygltf::Model& model_;
};

}  // namespace

uint64_t MemoryEstimate::total() const { return add(add(add(add(add(file, decoded), json), asset), transient), images); }

MemoryEstimate estimate_memory(const tinygltf::Model& model, bool decoded_images, bool kept_source) {
  Tally tally(model);
  for (const tinygltf::Mesh& mesh : model.meshes)
    for (const tinygltf::Primitive& p : mesh.primitives) tally.primitive(p, kept_source);
  for (const tinygltf::Skin& skin : model.skins) {
    if (skin.inverseBindMatrices >= 0) tally.read(skin.inverseBindMatrices, 0);
    tally.e.asset = add(tally.e.asset, mul(skin.joints.size(), sizeof(Mat4<double>) + sizeof(int)));
  }
  for (const tinygltf::Animation& animation : model.animations)
    for (const tinygltf::AnimationChannel& channel : animation.channels) {
      if (channel.sampler < 0 || size_t(channel.sampler) >= animation.samplers.size()) continue;
      const tinygltf::AnimationSampler& s = animation.samplers[size_t(channel.sampler)];
      tally.read(s.input, 4);  // each channel decodes its sampler's keys and values again
      tally.read(s.output, 4);
    }
  if (decoded_images)
    for (const tinygltf::Image& i : model.images)
      if (const auto size = declared_image_size(i.image))
        tally.e.images = add(tally.e.images, mul(mul(size->first, size->second), 4));
  return tally.finish();
}

}  // namespace dqskin::gltf
