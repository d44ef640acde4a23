// SPDX-License-Identifier: BSD-3-Clause
// voxlink.render(): one frame of a .vxl file through EGL, as `voxlink render` makes it (the
// same option handling: render/render_options.h), returned as an HxWx4 float32 array.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstring>
#include <optional>
#include <string>

#include "python/bindings.h"
#include "render/gl/gl_context.h"
#include "render/gl/voxlink_renderer.h"
#include "render/render_options.h"

namespace voxlink::python {
namespace {

Result<render::Image> renderFrame(const format::VoxLinkFile& file,
                                  const render::RenderOptions& options) {
  VOXLINK_ASSIGN_OR_RETURN(render::RenderSettings settings, options.settings(file));
  VOXLINK_ASSIGN_OR_RETURN(render::CameraSpec spec, options.cameraSpec(file));
  VOXLINK_ASSIGN_OR_RETURN(tf::TransferFunction tf, options.transferFunction(file));
  VOXLINK_ASSIGN_OR_RETURN(auto context, render::gl::createHeadlessContext());
  VOXLINK_ASSIGN_OR_RETURN(auto renderer, render::gl::VoxLinkRenderer::create(file));
  renderer->setTransferFunction(tf);
  const render::Camera camera = render::Camera::framing(renderer->geometry().worldBox(), spec);
  render::gl::RenderTarget target;
  VOXLINK_RETURN_IF_ERROR(renderer->render(camera, settings, target));
  return target.read();
}

// size="WxH" as the CLI's --size, or (width, height) as a tuple or list of two ints.
std::string sizeArgument(const py::object& size) {
  if (py::isinstance<py::str>(size)) return size.cast<std::string>();
  if (py::isinstance<py::tuple>(size) || py::isinstance<py::list>(size)) {
    const py::sequence pair = size.cast<py::sequence>();
    // An integer is what operator.index takes (int, NumPy integers), not a bool or a float.
    const auto integer = [](const py::handle& h) -> std::optional<std::string> {
      if (py::isinstance<py::bool_>(h)) return std::nullopt;
      PyObject* index = PyNumber_Index(h.ptr());
      if (!index) {
        PyErr_Clear();
        return std::nullopt;
      }
      return py::str(py::reinterpret_steal<py::object>(index)).cast<std::string>();
    };
    if (pair.size() == 2) {
      const auto w = integer(pair[0]), h = integer(pair[1]);
      if (w && h) return *w + "x" + *h;
    }
  }
  throw py::type_error("size must be (width, height) as two ints, or a 'WxH' string; got " +
                       py::repr(size).cast<std::string>());
}

py::array_t<float> render(const py::object& fileOrPath, const py::object& size,
                          const std::string& camera, const std::string& sampling,
                          const py::object& tf, const std::string& tfPreset) {
  const PyFile file = py::isinstance<PyFile>(fileOrPath) ? fileOrPath.cast<PyFile>()
                                                         : openFile(pathArgument(fileOrPath));
  if (!render::parseSampling(sampling))  // the CLI checks this in its option parser
    throw py::value_error("sampling must be voxel or trilinear, not '" + sampling + "'");
  render::RenderOptions options;
  options.size = sizeArgument(size);
  options.camera = camera;
  options.sampling = sampling;
  if (!tf.is_none()) options.tfPath = pathArgument(tf);
  options.tfPreset = tfPreset;
  Result<render::Image> image = [&] {
    py::gil_scoped_release release;
    return renderFrame(*file.file, options);
  }();
  if (!image) raise(image.error());
  py::array_t<float> out({py::ssize_t(image->height), py::ssize_t(image->width), py::ssize_t{4}});
  std::memcpy(out.mutable_data(), image->rgba.data(), image->rgba.size() * sizeof(float));
  return out;
}

}  // namespace

void bindRender(py::module_& m) {
  m.def("render", &render, py::arg("file"), py::kw_only(), py::arg("size") = "512x512",
        py::arg("camera") = "", py::arg("sampling") = "voxel", py::arg("tf") = py::none(),
        py::arg("tf_preset") = "",
        R"doc(Renders one frame headless (EGL) like `voxlink render`; returns HxWx4 float32
linear RGBA in the renderer's row order (row 0 is the image's first row as the CLI writes it).

file: a voxlink.File or a .vxl path (str, bytes or os.PathLike). size: (width, height) or
"WxH"; camera "AZ,EL[,DIST[,FOV]]" (empty: the
default view); sampling "voxel" or "trilinear"; tf: a transfer function JSON path (os.PathLike too), or
tf_preset: a preset name (as --tf-preset); neither: the file's default.)doc");
}

}  // namespace voxlink::python
