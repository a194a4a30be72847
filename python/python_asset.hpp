// A loaded file as the Python module holds it (internal to the Python module): the asset, the scene the
// commands work on, its mesh instances and the bake's vertex order, shared by the Python objects made from
// it, so that a clip outlives nothing it needs.
#pragma once

#include "dqskin/asset.hpp"
#include "dqskin/load.hpp"
#include "dqskin/skinning.hpp"
#include "../lib/write/vertex_sharing.hpp"

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace dqskin::python {

struct LoadedAsset {
  std::string path;
  LoadOptions load;
  Asset asset;
  int scene = -1;
  std::vector<MeshInstance> instances;
  SharedVertexLayout layout;  // the vertex order of the bake's ply, obj and vertex-animation outputs
};

using AssetHandle = std::shared_ptr<const LoadedAsset>;

// The Python class Asset: a handle on the loaded file (asset_binding.cpp, deform_binding.cpp).
class PyAsset {
public:
  explicit PyAsset(AssetHandle handle) : handle_(std::move(handle)) {}
  const AssetHandle& handle() const { return handle_; }

  std::string path() const;
  int scene() const;
  size_t vertices() const;
  pybind11::list scenes() const;
  pybind11::list skins() const;
  pybind11::list clips() const;
  // One clip by name or index (InputError naming the clips there are when none matches).
  pybind11::object clip(const std::variant<size_t, std::string>& which) const;
  std::string repr() const;

private:
  AssetHandle handle_;
};

}  // namespace dqskin::python
