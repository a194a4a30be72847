#include "python_errors.hpp"

#include "dqskin/error.hpp"
#include "dqskin/gpu_context.hpp"
#include "dqskin/memory_ceiling.hpp"

#include <new>

namespace dqskin::python {

namespace py = pybind11;

namespace {

// A Python class `name` deriving from `bases`, made in `module` as the class statement would make it.
py::object make_class(py::module_& module, const char* name, py::tuple bases, const char* doc) {
  py::dict namespace_;
  namespace_["__doc__"] = doc;
  namespace_["__module__"] = "dqskin";
  py::object type = py::reinterpret_borrow<py::object>(reinterpret_cast<PyObject*>(&PyType_Type));
  py::object cls = type(name, bases, namespace_);
  module.attr(name) = cls;
  return cls;
}

}  // namespace

void register_errors(py::module_& module) {
  // Held for the life of the process (the translator may run until the interpreter ends): never released.
  static py::handle error, input_error, output_error, no_gpu;
  py::object builtins = py::module_::import("builtins");
  error = make_class(module, "Error", py::make_tuple(builtins.attr("Exception")), "Any error dqskin reports.").release();
  input_error = make_class(module, "InputError", py::make_tuple(error, builtins.attr("ValueError")),
                           "A file or an argument dqskin refuses: the command line's one-line message.").release();
  output_error = make_class(module, "OutputError", py::make_tuple(error, builtins.attr("OSError")),
                            "A file dqskin cannot write.").release();
  no_gpu = make_class(module, "NoGpuContext", py::make_tuple(error, builtins.attr("RuntimeError")),
                      "No GL context for the backend asked (egl, osmesa); backend='auto' falls back to the CPU.").release();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(input_error.ptr(), e.what());
    } catch (const OutputError& e) {
      PyErr_SetString(output_error.ptr(), e.what());
    } catch (const NoGpuContext& e) {
      PyErr_SetString(no_gpu.ptr(), e.what());
    } catch (const std::bad_alloc&) {
      PyErr_SetString(PyExc_MemoryError, out_of_memory_message().c_str());
    }
  });
}

}  // namespace dqskin::python
