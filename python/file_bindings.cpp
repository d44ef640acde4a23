// SPDX-License-Identifier: BSD-3-Clause
// voxlink.File: info(), voxels(), to_dense(), validate() over a validated .vxl file.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>

#include "convert/vdb_footprint.h"
#include "format/gradient_codec.h"
#include "format/source_value.h"
#include "format/validator.h"
#include "format/voxel_locator.h"
#include "pack/open_file.h"
#include "pack/packed_file.h"
#include "python/bindings.h"
#include "report/dense_export.h"
#include "report/footprint.h"

namespace voxlink::python {
namespace {

py::object jsonLoads(const std::string& text) {
  return py::module_::import("json").attr("loads")(text);
}

// voxels() and to_dense() index VALU by voxel; a scene's VALU is indexed by volume slot.
void requireVolumeFile(const format::VoxLinkFile& f, const char* what) {
  if (f.isScene())
    raise(makeError(ErrorCode::kUnsupported, f.path(), ": ", what,
                    " reads volume files (version 1); this is a scene (version 2)"));
}

py::dict info(const PyFile& self, bool vdb) {
  report::FootprintReport report = report::computeFootprint(*self.file);
  if (vdb) {
    Result<report::PeerFootprint> peer = [&] {
      py::gil_scoped_release release;
      return convert::measureVdbFootprint(*self.file);
    }();
    if (!peer)
      raise(makeError(peer.code(), peer.message(), " (info(vdb=False) reports without it)"));
    report.peer = *peer;
  }
  return jsonLoads(report::footprintJson(report));
}

py::tuple voxels(const PyFile& self) {
  const format::VoxLinkFile& f = *self.file;
  requireVolumeFile(f, "voxels()");
  const py::ssize_t n = static_cast<py::ssize_t>(f.voxelCount());
  py::array_t<int32_t> ijk({n, py::ssize_t{3}});
  py::array_t<double> values(n);
  py::array_t<float> gradients({n, py::ssize_t{3}});
  int32_t* p = ijk.mutable_data();
  double* v = values.mutable_data();
  float* g = gradients.mutable_data();
  {
    py::gil_scoped_release release;
    const std::span<const uint16_t> codes = f.gradientCodes();
    format::VoxelLocator(f).forEachVoxel([&](uint32_t x, uint32_t y, uint32_t z, uint64_t i) {
      p[3 * i] = static_cast<int32_t>(x);
      p[3 * i + 1] = static_cast<int32_t>(y);
      p[3 * i + 2] = static_cast<int32_t>(z);
      v[i] = f.value(i);
      const std::array<float, 3> d = format::decodeGradient(codes[i]);
      for (int c = 0; c < 3; ++c) g[3 * i + c] = d[c];
    });
  }
  return py::make_tuple(ijk, values, gradients);
}

template <class T>
py::array denseOf(const format::VoxLinkFile& f, double fill) {
  raiseIfError(report::checkFill(f.sourceType(), fill, f.path(), "fill"));
  const uint32_t* dims = f.header().dims;
  py::array_t<T> out(std::vector<py::ssize_t>{dims[2], dims[1], dims[0]});
  T* d = out.mutable_data();
  {
    py::gil_scoped_release release;
    std::fill(d, d + uint64_t{dims[0]} * dims[1] * dims[2], static_cast<T>(fill));
    format::VoxelLocator(f).forEachVoxel([&](uint32_t x, uint32_t y, uint32_t z, uint64_t i) {
      // Rounded and clamped as the dense export does (format/source_value.h).
      d[(uint64_t{z} * dims[1] + y) * dims[0] + x] = static_cast<T>(asSourceValueOf<T>(f.value(i)));
    });
  }
  return out;
}

py::array toDense(const PyFile& self, double fill) {
  const format::VoxLinkFile& f = *self.file;
  requireVolumeFile(f, "to_dense()");
  switch (f.sourceType()) {
    case ScalarType::kU8:
      return denseOf<uint8_t>(f, fill);
    case ScalarType::kI8:
      return denseOf<int8_t>(f, fill);
    case ScalarType::kU16:
      return denseOf<uint16_t>(f, fill);
    case ScalarType::kI16:
      return denseOf<int16_t>(f, fill);
    case ScalarType::kU32:
      return denseOf<uint32_t>(f, fill);
    case ScalarType::kI32:
      return denseOf<int32_t>(f, fill);
    case ScalarType::kF32:
      return denseOf<float>(f, fill);
    case ScalarType::kF64:
      return denseOf<double>(f, fill);
  }
  raise(makeError(ErrorCode::kUnsupported, f.path(), ": source type ", int(f.sourceType()),
                  " has no NumPy dtype"));
}

py::dict validate(const PyFile& self) {
  Result<format::ValidationReport> report = [&] {
    py::gil_scoped_release release;
    return format::validateFile(*self.file);
  }();
  if (!report) raise(report.error());
  py::dict d;
  d["bytes_checked"] = report->bytesChecked;
  d["voxels_checked"] = report->voxelsChecked;
  d["bricks_checked"] = report->bricksChecked;
  return d;
}

py::dict pack(const PyFile& self, const py::object& path, bool fast) {
  const std::string out = pathArgument(path);
  Result<pack::PackReport> report = [&] {
    py::gil_scoped_release release;
    pack::PackOptions options;
    options.predictGradients = !fast;
    return pack::packFile(*self.file, out, options);
  }();
  if (!report) raise(report.error());
  py::dict d;
  d["bytes"] = report->inputBytes;
  d["packed_bytes"] = report->outputBytes;
  d["pack_seconds"] = report->packSeconds;
  d["predict_seconds"] = report->predictSeconds;
  return d;
}

}  // namespace

std::string pathArgument(const py::object& path) {
  const std::string text = py::module_::import("os").attr("fsdecode")(path).cast<std::string>();
  if (text.find('\0') != std::string::npos)
    throw py::value_error("path contains a NUL character: " + py::repr(path).cast<std::string>());
  return text;
}

PyFile openFile(const std::string& path) {
  Result<format::VoxLinkFile> file = [&] {
    py::gil_scoped_release release;
    return pack::readValidatedFile(path);  // a copy: the file may change on disk later
  }();
  if (!file) raise(file.error());
  return PyFile{std::make_shared<const format::VoxLinkFile>(std::move(*file))};
}

void bindFile(py::module_& m) {
  py::class_<PyFile>(
      m, "File",
      "A validated VoxLink (.vxl) file, held in memory (a private copy: changing the file on disk "
      "later does not affect it).")
      .def_property_readonly(
          "path", [](const PyFile& f) { return f.file->path(); }, "The file's path.")
      .def_property_readonly(
          "dims",
          [](const PyFile& f) {
            const auto& d = f.file->header().dims;
            return py::make_tuple(d[0], d[1], d[2]);
          },
          "Source dims (x, y, z).")
      .def_property_readonly(
          "spacing",
          [](const PyFile& f) {
            const double* s = f.file->header().spacing;
            return py::make_tuple(s[0], s[1], s[2]);
          },
          "World size of a voxel along x, y, z.")
      .def_property_readonly(
          "origin",
          [](const PyFile& f) {
            const double* o = f.file->header().origin;
            return py::make_tuple(o[0], o[1], o[2]);
          },
          "World position of voxel (0, 0, 0)'s centre.")
      .def("info", &info, py::arg("vdb") = true,
           "The memory footprint report as a dict, the same as `voxlink info --json`; vdb=False "
           "skips the OpenVDB peer (like --no-vdb).")
      .def("voxels", &voxels,
           "(ijk, values, gradients): int32 Nx3 voxel coordinates (x, y, z), float64 N values in "
           "source units, float32 Nx3 decoded unit gradients ((0,0,0) where the gradient is "
           "zero), in file order.")
      .def("to_dense", &toDense, py::arg("fill") = 0.0,
           "The classified volume as a dense array a[z][y][x] of the source's type; removed "
           "voxels hold `fill`.")
      .def("validate", &validate,
           "Checks every checksum and invariant again; returns the counts checked, raises "
           "voxlink.Error naming the section and field otherwise.")
      .def("pack", &pack, py::arg("path"), py::arg("fast") = false,
           "Writes the file packed (lossless, as `voxlink pack`; voxlink.open reads it back): "
           "returns bytes, packed_bytes, pack_seconds, predict_seconds. fast=True does not "
           "predict gradients (on CT twice as fast to load, files about 2.4x as large, not "
           "reliably faster to pack).")
      .def("__repr__", [](const PyFile& f) {
        const auto& d = f.file->header().dims;
        return "<voxlink.File '" + f.file->path() + "' " + std::to_string(d[0]) + "x" +
               std::to_string(d[1]) + "x" + std::to_string(d[2]) + ", " +
               std::to_string(f.file->voxelCount()) + " voxels>";
      });
  m.def(
      "open", [](const py::object& path) { return openFile(pathArgument(path)); }, py::arg("path"),
      "Opens and validates a .vxl file (as `voxlink render` and `info` do).");
}

}  // namespace voxlink::python
