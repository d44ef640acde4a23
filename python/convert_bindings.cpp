// SPDX-License-Identifier: BSD-3-Clause
// voxlink.convert(): a NumPy array or a file path -> a .vxl file, through the same converter
// and classification as `voxlink convert` (the same options give the same bytes).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <stdlib.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "base/output_file.h"
#include "base/parallel_for.h"
#include "convert/converter.h"
#include "python/array_source.h"
#include "python/bindings.h"
#include "sources/readers/reader_common.h"
#include "tf/transfer_function.h"

namespace voxlink::python {
namespace {

// threshold=60, "60,200", (60, 200) as one [LO,HI] pair, or a list of those for a union.
std::string thresholdSpec(const py::handle& h) {
  if (py::isinstance<py::str>(h)) return h.cast<std::string>();
  if (py::isinstance<py::tuple>(h)) {
    auto pair = h.cast<std::vector<double>>();
    if (pair.size() != 2) throw py::value_error("threshold tuple must be (LO, HI)");
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g,%.17g", pair[0], pair[1]);
    return buf;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", h.cast<double>());
  return buf;
}

convert::Classification classificationFrom(const py::object& threshold, const py::object& tf,
                                           const py::object& keepOutside, bool keepAll,
                                           std::optional<double> mean,
                                           std::optional<double> sigma) {
  const int given = !threshold.is_none() + !tf.is_none() + !keepOutside.is_none() + keepAll;
  if (given != 1)
    throw py::value_error("give exactly one of threshold=, tf=, keep_outside=, keep_all=True");
  if (!threshold.is_none()) {
    std::vector<std::string> specs;
    if (py::isinstance<py::list>(threshold))
      for (const py::handle& h : threshold) specs.push_back(thresholdSpec(h));
    else
      specs.push_back(thresholdSpec(threshold));
    return valueOrRaise(convert::thresholdClassification(specs));
  }
  if (!tf.is_none())
    return convert::tfClassification(valueOrRaise(tf::loadTransferFunction(pathArgument(tf))));
  if (!keepOutside.is_none()) {
    auto range = keepOutside.cast<std::vector<double>>();
    if (range.size() != 2) throw py::value_error("keep_outside must be (LO, HI)");
    return valueOrRaise(convert::keepOutsideClassification(range[0], range[1], mean, sigma));
  }
  return convert::keepAllClassification();
}

std::optional<ScalarType> scalarTypeOfDtype(const py::dtype& dtype) {
  if (dtype.byteorder() == '>') return std::nullopt;  // not native on the machines we build for
  switch (dtype.kind()) {
    case 'u':
      if (dtype.itemsize() == 1) return ScalarType::kU8;
      if (dtype.itemsize() == 2) return ScalarType::kU16;
      if (dtype.itemsize() == 4) return ScalarType::kU32;
      break;
    case 'i':
      if (dtype.itemsize() == 1) return ScalarType::kI8;
      if (dtype.itemsize() == 2) return ScalarType::kI16;
      if (dtype.itemsize() == 4) return ScalarType::kI32;
      break;
    case 'f':
      if (dtype.itemsize() == 4) return ScalarType::kF32;
      if (dtype.itemsize() == 8) return ScalarType::kF64;
      break;
  }
  return std::nullopt;
}

// The NumPy array as a volume a[z][y][x]; refuses what the converter cannot read in place.
std::unique_ptr<sources::VolumeSource> arraySource(const py::array& a,
                                                   const std::array<double, 3>& spacing,
                                                   const std::array<double, 3>& origin) {
  if (a.ndim() != 3)
    throw py::value_error("convert: the array has " + std::to_string(a.ndim()) +
                          " dimensions; expected 3 (a[z][y][x])");
  // The limits `voxlink convert` applies to any input, before anything else: a memmap of
  // (512, 65536, 65536) ran for hours where the command line refuses the same dims at once.
  std::array<uint64_t, 3> dims{};
  for (int axis = 0; axis < 3; ++axis)
    dims[axis] = uint64_t(std::max<py::ssize_t>(a.shape(2 - axis), 0));
  raiseIfError(sources::checkDims(dims, "numpy array", "shape"));
  if (!(a.flags() & py::array::c_style))
    throw py::value_error(
        "convert: the array is not C-contiguous; pass numpy.ascontiguousarray(a)");
  const std::optional<ScalarType> type = scalarTypeOfDtype(a.dtype());
  if (!type)
    throw py::type_error("convert: dtype " + py::str(a.dtype()).cast<std::string>() +
                         " is not supported (uint8/16/32, int8/16/32, float32/64, native order)");
  sources::VolumeInfo info;
  for (int axis = 0; axis < 3; ++axis) info.dims[axis] = static_cast<uint32_t>(dims[axis]);
  info.type = *type;
  info.spacing = spacing;
  info.origin = origin;
  info.path = "numpy array";
  info.format = "numpy-array";
  return std::make_unique<ArraySource>(std::move(info), a.data());
}

// A Python exception taken out of the interpreter while C++ code finishes (the GIL released in
// between), then raised again. Every method must be called with the GIL held.
class PendingPythonError {
 public:
  PendingPythonError() = default;
  PendingPythonError(const PendingPythonError&) = delete;
  PendingPythonError& operator=(const PendingPythonError&) = delete;
  ~PendingPythonError() {
    if (type_) {
      py::gil_scoped_acquire gil;
      Py_XDECREF(type_);
      Py_XDECREF(value_);
      Py_XDECREF(traceback_);
    }
  }
  void fetch() {
    if (!type_) PyErr_Fetch(&type_, &value_, &traceback_);
    PyErr_Clear();
  }
  void raiseIfAny() {
    if (!type_) return;
    PyErr_Restore(type_, value_, traceback_);
    type_ = value_ = traceback_ = nullptr;
    throw py::error_already_set();
  }

 private:
  PyObject* type_ = nullptr;
  PyObject* value_ = nullptr;
  PyObject* traceback_ = nullptr;
};

// A fresh private folder for a file nobody named; removed once the file is read.
struct ScratchDir {
  std::filesystem::path dir;
  ScratchDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "voxlink-py-XXXXXX").string();
    if (!mkdtemp(pattern.data()))
      raise(makeError(ErrorCode::kIo, pattern, ": cannot create a temporary folder"));
    dir = pattern;
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(dir, ignored);
  }
};

PyFile convertAny(const py::object& input, const py::object& output, const py::object& threshold,
                  const py::object& tf, const py::object& keepOutside, bool keepAll,
                  std::optional<double> mean, std::optional<double> sigma, uint32_t brick,
                  const std::string& axis, const std::optional<std::string>& valueType,
                  double errorBound, unsigned threads, uint32_t slab, std::array<double, 3> spacing,
                  std::array<double, 3> origin) {
  if (brick != 4 && brick != 8 && brick != 16 && brick != 32)
    throw py::value_error("brick must be 4, 8, 16 or 32");
  if (axis != "x" && axis != "y" && axis != "z") throw py::value_error("axis must be x, y or z");
  // The reader's and the converter's parallel work, for this call: the same limit as --threads.
  const base::ThreadLimit limit(threads);
  convert::ConvertOptions options;
  options.brickSize = brick;
  options.axis = static_cast<format::Axis>(axis[0] - 'x');
  options.classification = classificationFrom(threshold, tf, keepOutside, keepAll, mean, sigma);
  options.threads = threads;
  options.slabSlices = slab;
  options.errorBound = errorBound;
  if (valueType) {
    options.storedType = parseStoredName(*valueType);
    if (!options.storedType) throw py::value_error("value_type must be u8, u16, f16 or f32");
  }

  std::optional<ScratchDir> scratch;
  std::string outPath;
  if (output.is_none()) {
    scratch.emplace();
    outPath = (scratch->dir / "converted.vxl").string();
  } else {
    outPath = pathArgument(output);
  }

  std::unique_ptr<sources::VolumeSource> source;
  py::array array;  // keeps the buffer alive while the GIL is released
  std::vector<std::string> inputs;
  if (py::isinstance<py::array>(input)) {
    array = input.cast<py::array>();
    source = arraySource(array, spacing, origin);
  } else {
    const std::string path = pathArgument(input);
    inputs.push_back(path);
    Result<std::unique_ptr<sources::VolumeSource>> opened = [&] {
      py::gil_scoped_release release;
      return sources::openVolume(path, options.sourceOptions);
    }();
    source = valueOrRaise(std::move(opened));
  }
  raiseIfError(base::checkOutputTarget(outPath, inputs));
  if (!inputs.empty())
    raiseIfError(base::checkOutputTarget(outPath, inputs.back(), source->info().files));
  {
    // Ctrl-C: the converter reports after every slab; the report takes the GIL back for a
    // moment and runs Python's signal handlers. One that raises (KeyboardInterrupt) cancels the
    // conversion at the next slab, and its exception is raised here, with nothing written.
    std::atomic<bool> cancel{false};
    PendingPythonError interrupt;
    options.cancel = &cancel;
    options.progress = [&](double, const char*) {
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) {
        interrupt.fetch();
        cancel.store(true);
      }
    };
    Result<convert::ConvertSummary> summary = [&] {
      py::gil_scoped_release release;
      return convert::convertVolume(*source, options, outPath);
    }();
    interrupt.raiseIfAny();
    if (!summary) raise(summary.error());
  }
  return openFile(outPath);  // read into memory: the scratch folder may go
}

}  // namespace

void bindConvert(py::module_& m) {
  m.def("convert", &convertAny, py::arg("input"), py::kw_only(), py::arg("output") = py::none(),
        py::arg("threshold") = py::none(), py::arg("tf") = py::none(),
        py::arg("keep_outside") = py::none(), py::arg("keep_all") = false,
        py::arg("mean") = py::none(), py::arg("sigma") = py::none(), py::arg("brick") = 8,
        py::arg("axis") = "z", py::arg("value_type") = py::none(), py::arg("error_bound") = 0.0,
        py::arg("threads") = 0, py::arg("slab") = 64,
        py::arg("spacing") = std::array<double, 3>{1, 1, 1},
        py::arg("origin") = std::array<double, 3>{0, 0, 0},
        R"doc(Pre-classifies a dense volume into a VoxLink file and opens it.

input: a 3-D NumPy array a[z][y][x] (C-contiguous; uint8/16/32, int8/16/32, float32/64) or a
  path any `voxlink convert` reader opens. spacing/origin (x, y, z) apply to arrays only.
Exactly one of threshold= (60, "60,200", (60, 200), or a list for a union), tf= (a transfer
  function JSON path), keep_outside=(LO, HI) [mean=, sigma=], keep_all=True.
brick, axis, value_type ("u8", "u16", "f16", "f32"), error_bound, threads, slab: as the CLI's
  options; the same input and options give a file byte-identical to `voxlink convert`.
output: the .vxl path to write (temp file, then rename); None keeps it only in memory.)doc");
}

}  // namespace voxlink::python
