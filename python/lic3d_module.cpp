// SPDX-License-Identifier: BSD-3-Clause
// The Python module lic3d (docs/PYTHON.md): LIC volumes and pictures of numpy arrays, made by the
// engine the command line uses. Parameters are the command line's long options with underscores
// (length=30 is --length 30), parsed and checked by the same code, so a refused value raises
// ValueError with the message `lic3d` prints.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "gpu/device_choice.h"
#include "python/arguments.h"
#include "python/renderer.h"

namespace lic3d::python {
namespace {

// lic3d.compute and lic3d.render: a Renderer used once.
py::array_t<float> compute(const py::object& vectors, const py::object& spacing,
                           const py::object& origin, const py::object& noise,
                           const py::object& scalars, const py::object& session,
                           const py::object& progress, const py::kwargs& params) {
  Renderer once(vectors, spacing, origin, noise, scalars, py::none(), py::dict(), false);
  return once.compute(session, progress, params);
}

py::array_t<std::uint8_t> render(const py::object& vectors, const py::object& spacing,
                                 const py::object& origin, const py::object& noise,
                                 const py::object& scalars, const py::object& session,
                                 const py::object& progress, const py::kwargs& params) {
  Renderer once(vectors, spacing, origin, noise, scalars, py::none(), py::dict(), false);
  return once.render(session, progress, params);
}

py::object sessionDict(const py::object& session, const py::kwargs& params) {
  const Request request = parseRequest("render", session, py::none(), params);
  return py::module_::import("json").attr("loads")(sessionToJson(request.session()));
}

py::list devices() {
  py::list list;
  for (const DeviceInfo& info : take(listDevices())) {
    py::dict device;
    device["index"] = info.index;
    device["name"] = info.name;
    device["type"] = deviceTypeName(info.type);
    list.append(device);
  }
  return list;
}

}  // namespace
}  // namespace lic3d::python

PYBIND11_MODULE(lic3d, module) {
  using namespace lic3d::python;
  module.doc() =
      "3D Line Integral Convolution of vector fields with Vulkan (docs/PYTHON.md).\n\n"
      "Parameters are the long options of `lic3d compute --help` and `lic3d render --help` with "
      "underscores: length=30, integrator='rk4', noise_filter='nearest', look='streamlines', "
      "size=(800, 600). A refused value raises ValueError with the message of the command line.";
  module.attr("__version__") = LIC3D_VERSION;
  module.def("compute", &compute, py::arg("vectors") = py::none(), py::kw_only(),
             py::arg("spacing") = 1.0, py::arg("origin") = 0.0, py::arg("noise") = py::none(),
             py::arg("scalars") = py::none(), py::arg("session") = py::none(),
             py::arg("progress") = py::none(),
             "compute(vectors=None, *, spacing=1.0, origin=0.0, noise=None, scalars=None, "
             "session=None, progress=None, **params) -> numpy.ndarray\n\n"
             "The LIC volume of `vectors` (numbers shaped (nz, ny, nx, 3), x fastest) as "
             "float32 shaped (nz, ny, nx), as `lic3d compute` writes it. Without vectors, "
             "the field of field=... (an analytic field or a file). noise: an array "
             "(nz, ny, nx) of uint8, uint16 or float32 on the LIC grid, or a noise file; "
             "default seeded white noise. scalars: a dict of names to arrays (nz, ny, nx) on "
             "the vectors' grid that color_by= and opacity_by= can name (or give "
             "color_by=array). session: a dict (lic3d.session()) or a session "
             "file (JSON or a PNG lic3d wrote) the parameters then override. "
             "device='' picks as `lic3d --device` does, devices='all' spreads the LIC over "
             "several as `lic3d compute --devices` does; cpu=True uses the CPU reference. "
             "progress: a callable that gets the finished fraction of the LIC now and then "
             "(from another thread). The GIL is released while the LIC is made; Ctrl-C, or an "
             "exception from progress, stops the work at its next slab or brick and is raised. "
             "Each call opens the device anew: lic3d.Renderer keeps it, and what was made, "
             "between calls.");
  module.def("render", &render, py::arg("vectors") = py::none(), py::kw_only(),
             py::arg("spacing") = 1.0, py::arg("origin") = 0.0, py::arg("noise") = py::none(),
             py::arg("scalars") = py::none(), py::arg("session") = py::none(),
             py::arg("progress") = py::none(),
             "render(vectors=None, *, spacing=1.0, origin=0.0, noise=None, scalars=None, "
             "session=None, progress=None, **params) -> numpy.ndarray\n\n"
             "The picture `lic3d render` makes, as uint8 RGBA shaped (height, width, 4), "
             "rows top to bottom. Arguments as for compute, plus the view parameters "
             "(look, size, azimuth, elevation, colormap, ...).");
  bindRenderer(module);
  module.def("session", &sessionDict, py::arg("session") = py::none(),
             "session(session=None, **params) -> dict\n\n"
             "The whole session the parameters make (over `session`, a dict or file), as the "
             "dict that compute and render take and session files hold.");
  module.def("devices", &devices,
             "devices() -> list of dict\n\nThe Vulkan devices lic3d can use: index, name, type "
             "(device=index or a part of the name chooses one).");
}
