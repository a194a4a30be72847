// The module's exceptions (internal to the Python module): dqskin's errors as Python classes carrying the
// command line's one-line message (without its "dqskin: " prefix), so that a pipeline catches what it can
// act on: InputError (a file or an argument the CLI refuses; also a ValueError), OutputError (a file that
// cannot be written; also an OSError), NoGpuContext (no GL context for the backend asked; also a
// RuntimeError), all of them dqskin.Error.
#pragma once

#include <pybind11/pybind11.h>

namespace dqskin::python {

// Adds the classes to `module` and registers the translation of the C++ exceptions.
void register_errors(pybind11::module_& module);

}  // namespace dqskin::python
