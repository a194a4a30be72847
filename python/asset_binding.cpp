// dqskin.load and what it returns: the file's scenes, skins and their joints, and its clips with their
// names, durations and key times, as plain Python objects (docs/python.md).
#include "interruptible.hpp"
#include "python_asset.hpp"

#include "../lib/base/byte_size.hpp"
#include "dqskin/animation.hpp"
#include "dqskin/error.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>

#include <algorithm>
#include <set>
#include <variant>

namespace dqskin::python {

namespace py = pybind11;

namespace {

std::string node_name(const Asset& asset, int node) {
  const std::string& name = asset.nodes[size_t(node)].name;
  return name.empty() ? "node " + std::to_string(node) : name;
}

// max_memory as bytes or as the command line writes it ("512M").
uint64_t byte_budget(const std::variant<uint64_t, std::string>& value) {
  if (const uint64_t* bytes = std::get_if<uint64_t>(&value)) {
    if (*bytes == 0) throw InputError("max_memory must be above 0 bytes");
    return *bytes;
  }
  return parse_byte_size(std::get<std::string>(value), "max_memory");
}

py::dict clip_object(const Asset& asset, size_t index) {
  const Clip& clip = asset.clips[index];
  std::set<float> keys;
  for (const Channel& c : clip.channels) keys.insert(c.times.begin(), c.times.end());
  py::array_t<double> key_times(py::ssize_t(keys.size()));
  std::copy(keys.begin(), keys.end(), key_times.mutable_data());
  py::dict d;
  d["index"] = index;
  d["name"] = clip.name;
  d["duration"] = clip.last_key;
  d["key_times"] = key_times;
  return d;
}

}  // namespace

// A clip as Python sees it: index, name, duration (its last key time, seconds) and key_times (every key
// time of its channels, sorted, as float64).
py::object make_clip(const AssetHandle& asset, size_t index) {
  const py::object types = py::module_::import("types");
  return types.attr("SimpleNamespace")(**clip_object(asset->asset, index));
}

std::string PyAsset::path() const { return handle_->path; }
int PyAsset::scene() const { return handle_->scene; }
size_t PyAsset::vertices() const { return handle_->layout.vertices; }

py::list PyAsset::scenes() const {
  py::list out;
  const py::object ns = py::module_::import("types").attr("SimpleNamespace");
  for (size_t i = 0; i < handle_->asset.scenes.size(); ++i)
    out.append(ns(py::arg("index") = i, py::arg("name") = handle_->asset.scenes[i].name));
  return out;
}

py::list PyAsset::skins() const {
  py::list out;
  const py::object ns = py::module_::import("types").attr("SimpleNamespace");
  const Asset& a = handle_->asset;
  for (size_t i = 0; i < a.skins.size(); ++i) {
    py::list joints;
    for (int node : a.skins[i].joints) joints.append(node_name(a, node));
    out.append(ns(py::arg("index") = i, py::arg("name") = a.skins[i].name, py::arg("joints") = joints));
  }
  return out;
}

py::list PyAsset::clips() const {
  py::list out;
  for (size_t i = 0; i < handle_->asset.clips.size(); ++i) out.append(make_clip(handle_, i));
  return out;
}

py::object PyAsset::clip(const std::variant<size_t, std::string>& which) const {
  const std::string text = std::holds_alternative<size_t>(which) ? std::to_string(std::get<size_t>(which))
                                                                   : std::get<std::string>(which);
  if (text == "all") throw InputError("clip: give one clip's name or index, not all");
  try {
    return make_clip(handle_, select_clips(handle_->asset, text).front());
  } catch (const InputError& e) {
    throw InputError(handle_->path + ": " + e.what());
  }
}

std::string PyAsset::repr() const {
  return "<dqskin.Asset " + handle_->path + ": " + std::to_string(handle_->asset.clips.size()) + " clips, " +
         std::to_string(handle_->asset.skins.size()) + " skins, " + std::to_string(handle_->layout.vertices) + " vertices>";
}

void register_deform_method(py::class_<PyAsset>& cls);

void register_asset(py::module_& module) {
  py::class_<PyAsset> asset(module, "Asset", "A loaded glTF file: its scenes, skins and clips, ready to deform.");
  asset.def_property_readonly("path", &PyAsset::path, "The file loaded.")
      .def_property_readonly("scene", &PyAsset::scene, "The scene deformed: the file's default scene, else 0 (-1: none).")
      .def_property_readonly("scenes", &PyAsset::scenes, "The scenes: objects with index and name.")
      .def_property_readonly("skins", &PyAsset::skins, "The skins: objects with index, name and joints (node names).")
      .def_property_readonly("clips", &PyAsset::clips,
                             "The animations: objects with index, name, duration (s) and key_times (float64 array).")
      .def_property_readonly("vertices", &PyAsset::vertices,
                             "Vertices of a deformed frame, in the order of the bake's ply output.")
      .def("clip", &PyAsset::clip, py::arg("which"), "One clip by name or index.")
      .def("__repr__", &PyAsset::repr);
  register_deform_method(asset);

  module.def(
      "load",
      [](const std::string& path, std::optional<std::variant<std::string, std::vector<std::string>>> resource_root,
         std::optional<std::variant<uint64_t, std::string>> max_memory) {
        auto loaded = std::make_shared<LoadedAsset>();
        loaded->path = path;
        if (resource_root) {
          if (const std::string* one = std::get_if<std::string>(&*resource_root)) loaded->load.resource_roots = {*one};
          else loaded->load.resource_roots = std::get<std::vector<std::string>>(*resource_root);
        }
        if (max_memory) loaded->load.max_memory = byte_budget(*max_memory);
        run_interruptible([&](const std::atomic<bool>&) {
          try {
            loaded->asset = load_asset(path, loaded->load);
            loaded->scene = choose_scene(loaded->asset, -1);
            loaded->instances = mesh_instances(loaded->asset, loaded->scene);
            loaded->layout = shared_vertex_layout(loaded->asset, loaded->instances);
          } catch (const InputError& e) {
            throw InputError(path + ": " + e.what());  // as the command line prints it
          }
        });
        // What the CLI prints as "dqskin: FILE: warning: …", as Python warnings at the caller's line.
        const py::object warn = py::module_::import("warnings").attr("warn");
        const py::object category = py::module_::import("dqskin").attr("Warning");
        for (const std::string& w : loaded->asset.warnings) warn(path + ": " + w, category, 1);
        return PyAsset(std::move(loaded));
      },
      py::arg("path"), py::arg("resource_root") = py::none(), py::arg("max_memory") = py::none(),
      "load(path, resource_root=None, max_memory=None) -> Asset\n\n"
      "Loads a .gltf, .glb or .vrm file as `dqskin bake` does. resource_root: folders (a list of paths) its\n"
      "external buffers and images may also come from (a path or a list); max_memory: the most loading may take, in bytes or as\n"
      "the command line writes it ('512M'; default 2G). Raises InputError with the command line's message for\n"
      "a file it refuses.");
}

}  // namespace dqskin::python
