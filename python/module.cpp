// `import dqskin`: the module's entry point. What each part adds is in its own file: the errors
// (python_errors.cpp), loading and the asset's description (asset_binding.cpp), deforming
// (deform_binding.cpp, the Asset's deform method), the commands (cli_binding.cpp).
#include "python_errors.hpp"

#include "dqskin/version.hpp"

#include <pybind11/pybind11.h>

namespace dqskin::python {
void register_asset(pybind11::module_& module);
void register_commands(pybind11::module_& module);
}  // namespace dqskin::python

PYBIND11_MODULE(dqskin, module) {
  // Each docstring starts with the call as a user writes it; pybind11's generated C++-typed line would
  // come first and read worse.
  pybind11::options options;
  options.disable_function_signatures();
  module.doc() =
      "dqskin: glTF 2.0 skinned animation as dual quaternions, deformed on the GPU or the CPU.\n\n"
      "    asset = dqskin.load('Fox.glb')\n"
      "    walk = asset.clip('Walk')\n"
      "    frames = asset.deform(walk, walk.key_times)   # frames.positions: frames x vertices x 3\n\n"
      "Errors are dqskin.Error and its kin (InputError, OutputError, NoGpuContext), each with the command\n"
      "line's one-line message.";
  module.attr("__version__") = dqskin::kVersion;
  dqskin::python::register_errors(module);
  dqskin::python::register_asset(module);
  dqskin::python::register_commands(module);
}
