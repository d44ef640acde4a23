// SPDX-License-Identifier: BSD-3-Clause
// The `voxlink` Python module: open, convert and render VoxLink files from NumPy code.
#include "python/bindings.h"

namespace voxlink::python {
namespace {

struct ErrorTag {};

// Leaked on purpose: a static py::object would be released after the interpreter is gone.
py::object*& errorType() {
  static py::object* type = nullptr;
  return type;
}

}  // namespace

void raise(const Error& error) {
  PyErr_SetString(errorType()->ptr(), error.message.c_str());
  throw py::error_already_set();
}

void bindError(py::module_& m) {
  errorType() = new py::exception<ErrorTag>(m, "Error", PyExc_RuntimeError);
  errorType()->attr("__doc__") =
      "A VoxLink library error; the message is the one `voxlink` prints.";
}

}  // namespace voxlink::python

PYBIND11_MODULE(voxlink, m) {
  m.doc() =
      "VoxLink sparse volumes from Python: convert dense NumPy arrays or files, read the voxels, "
      "values and gradients back, validate, and render headless (EGL).";
  voxlink::python::bindError(m);
  voxlink::python::bindFile(m);
  voxlink::python::bindConvert(m);
#ifdef VOXLINK_WITH_VIEWER
  voxlink::python::bindRender(m);
#endif
}
