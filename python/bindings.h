// SPDX-License-Identifier: BSD-3-Clause
// Pieces of the `voxlink` Python module, one file per concept: the File class, convert(),
// render(). Library errors become voxlink.Error with the library's one-line message.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>

#include "base/error.h"
#include "format/voxlink_file.h"

namespace voxlink::python {

namespace py = pybind11;

// The Python-visible exception type (a subclass of RuntimeError), set when the module loads.
[[noreturn]] void raise(const Error& error);

template <class T>
T valueOrRaise(Result<T> result) {
  if (!result) raise(result.error());
  return std::move(*result);
}

inline void raiseIfError(const Status& status) {
  if (!status) raise(status.error());
}

// A path argument as the os module takes it (str, bytes or os.PathLike; TypeError otherwise,
// where str(None) used to become a file named "None"), refused with ValueError if it holds a NUL
// (the C library would silently open the part before it).
std::string pathArgument(const py::object& path);

// What a Python File holds: a validated file, shared by the arrays and renders made from it.
struct PyFile {
  std::shared_ptr<const format::VoxLinkFile> file;
};

// Opens and validates like every command that reads a .vxl (`voxlink render`, `info`, ...).
PyFile openFile(const std::string& path);

void bindError(py::module_& m);
void bindFile(py::module_& m);
void bindConvert(py::module_& m);
void bindRender(py::module_& m);

}  // namespace voxlink::python
