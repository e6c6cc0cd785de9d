// SPDX-License-Identifier: BSD-3-Clause
#include "python/renderer.h"

#include <pybind11/stl.h>

#include "core/parallel.h"
#include "jobs/bricks.h"
#include "lic/lic_reference.h"
#include "loading/scalars.h"

namespace lic3d::python {

bool Renderer::InputsKey::operator==(const InputsKey& other) const {
  return session.field == other.session.field && session.noise == other.session.noise &&
         session.timeSteps == other.session.timeSteps && options == other.options &&
         cpu == other.cpu;
}

Renderer::Renderer(const py::object& vectors, const py::object& spacing, const py::object& origin,
                   const py::object& noise, const py::object& scalars, const py::object& session,
                   const py::dict& params, bool keep)
    : keep_(keep), session_(session), params_(params) {
  if (!vectors.is_none()) vectors_ = fieldOf(vectors, spacing, origin);
  if (py::isinstance<py::array>(noise)) {
    noise_ = noiseOf(noise);
    noiseFile_ = py::none();
  } else {
    noiseFile_ = noise;
  }
  arrays_ = heldScalars(scalars, params_);
  if (!keep_) return;
  checkKeywords(params_, "lic3d.Renderer()");
  // The devices now: their errors before any work, their start-up out of the calls' time.
  std::vector<PointScalars> none;
  const Request opening = request("compute", py::none(), py::dict(), none);
  if (opening.options->cpu) return;
  const py::gil_scoped_release unlocked;
  take(openDevices(opening));
}

Renderer::~Renderer() {
  // The renderer before the contexts it was made on.
  renderer_.reset();
  inputs_.reset();
}

Request Renderer::request(const char* command, const py::object& session, const py::dict& params,
                          std::vector<PointScalars>& callArrays) const {
  checkOpen();
  if (keep_)
    for (const char* keyword : {"device", "devices"})
      if (params.contains(keyword))
        throw py::type_error(std::string("Renderer.") + command + "() got the keyword argument '" +
                             keyword + "': a Renderer's devices are chosen when it is made");
  py::dict own = py::dict(params);
  callArrays = heldScalars(py::none(), own);
  Request made =
      parseRequest(command, session.is_none() ? session_ : session, noiseFile_, own, params_);
  checkFieldChoice(made, vectors_.has_value(), noise_.has_value());
  const std::string& devices = made.options->devices;
  if (!devices.empty() && made.options->cpu)
    throw py::value_error("--devices " + devices + ": --cpu computes on the CPU, not on devices");
  if (!devices.empty() && !made.global().device.empty())
    throw py::value_error("--device " + made.global().device + " --devices " + devices +
                          ": give one device (--device) or several (--devices), not both");
  if (!keep_ && !devices.empty() && std::string_view(command) == "render")
    throw py::value_error("--devices " + devices +
                          ": lic3d.render draws on one device (device=...); lic3d.compute "
                          "spreads a LIC volume over several (a lic3d.Renderer with devices= "
                          "does both, drawing on the first)");
  return made;
}

void Renderer::checkOpen() const {
  if (closed_) throw std::runtime_error("the lic3d.Renderer is closed");
}

Result<void> Renderer::openDevices(const Request& request) {
  const std::string chosen = request.global().device + "|" + request.options->devices;
  if (!contexts_.empty()) {
    if (chosen != devicesChosen_)
      return inputError("device=, devices=: a Renderer keeps the devices it was made with");
    return {};
  }
  LIC3D_TRY_ASSIGN(contexts_, python::openDevices(request.global(), request.options->devices));
  devicesChosen_ = chosen;
  return {};
}

Result<SessionInputs*> Renderer::inputsFor(const Request& request,
                                           std::vector<PointScalars>&& callArrays) {
  const Session& session = request.session();
  InputsKey key{.session = session, .options = inputOptions(request), .cpu = request.options->cpu};
  if (vectors_) key.options = {};
  const bool made = !inputs_ || !inputsKey_ || !(*inputsKey_ == key);
  if (made) {
    inputs_.reset();
    inputsKey_.reset();
    Result<SessionInputs> loaded = [&]() -> Result<SessionInputs> {
      if (!vectors_) return loadSessionInputs(session, key.options);
      // A Renderer used once gives its arrays away; one kept copies them for later inputs.
      VectorField field = keep_ ? *vectors_ : std::move(*vectors_);
      std::optional<NoiseVolume> noise;
      if (noise_) noise = keep_ ? *noise_ : std::move(*noise_);
      return sessionInputsOf(session, std::move(field), std::move(noise), "vectors");
    }();
    if (!loaded) return loaded.error();
    inputs_ = std::move(loaded).value();
    inputsKey_ = key;
    ++inputsMade_;
    nonFinite_ = inputs_->info.nonFiniteVectors;
  }
  // The call's arrays beside the Renderer's, by name over them, where the inputs are new or a
  // call gave arrays of its own (this one or the one before); the scalars made of the arrays
  // before are loaded again. Otherwise the inputs keep the arrays they hold, uncopied.
  if (made || !callArrays.empty() || callArraysHeld_) {
    scalarsKey_.reset();
    inputs_->arrays = keep_ ? arrays_ : std::move(arrays_);  // used once: given away
    for (PointScalars& array : callArrays) {
      std::erase_if(inputs_->arrays, [&](const PointScalars& a) { return a.name == array.name; });
      inputs_->arrays.push_back(std::move(array));
    }
    callArraysHeld_ = !callArrays.empty();
  }
  return &*inputs_;
}

Result<LicRenderer*> Renderer::rendererFor(const Request& request, SessionInputs& inputs) {
  const Session& session = request.session();
  if (renderer_ && rendererPrecision_ != session.precision) dropRenderer();
  bool first = false;
  if (!renderer_) {
    LIC3D_TRY_ASSIGN(renderer_, LicRenderer::create(contexts_.front(), {session.precision}));
    rendererPrecision_ = session.precision;
    ++renderersMade_;
    rendererInputs_ = 0;
    scalarsKey_.reset();
  }
  if (rendererInputs_ != inputsMade_) {
    first = true;
    rendererInputs_ = inputsMade_;
    scalarsKey_.reset();
  }
  const Result<void> moved =
      moveToTime(inputs, session, session.time, *renderer_, first, request.options->cpu);
  if (!moved) {
    rendererInputs_ = 0;  // given in full again next time
    return moved.error();
  }
  return &*renderer_;
}

Result<void> Renderer::checkValidation() const {
  for (const Context& context : contexts_) LIC3D_TRY(python::checkValidation(context));
  return {};
}

Result<ScalarVolume> Renderer::licVolume(const Request& request,
                                         std::vector<PointScalars>&& callArrays,
                                         const ProgressCallback& progress) {
  const Session& session = request.session();
  LIC3D_TRY_ASSIGN(SessionInputs * inputs, inputsFor(request, std::move(callArrays)));
  if (request.options->cpu) {
    if (inputs->series) {
      LIC3D_TRY_ASSIGN(inputs->field, hostFieldAt(*inputs, session, session.time));
    }
    return computeLicReference(inputs->field, inputs->noise, session.lic, 0, progress);
  }
  LIC3D_TRY(openDevices(request));
  std::vector<const Context*> devices;
  for (const Context& context : contexts_) devices.push_back(&context);
  LicVolumeOptions options{.deviceCap = request.options->memoryBudget};
  // A grid the first device holds whole is made with the kept renderer: its field textures and
  // LIC volume stay for the next call. Else in bricks spread over the devices, as lic3d compute,
  // with the device memory the renderer held given back first.
  const bool whole = checkRequestMemory(contexts_.front(), session, inputs->field.dims,
                                        {.volumeReadback = true,
                                         .timeSeries = inputs->series.has_value(),
                                         .deviceCap = request.options->memoryBudget})
                         .ok();
  if (whole && keep_) {
    LIC3D_TRY_ASSIGN(options.renderer, rendererFor(request, *inputs));
  } else {
    dropRenderer();
  }
  Result<LicVolumeRun> run = computeLicVolume(devices, session, *inputs, options, progress);
  LIC3D_TRY(checkValidation());
  if (!run) return run.error();
  return std::move(run->volume);
}

Result<RgbaImage> Renderer::picture(const Request& request, std::vector<PointScalars>&& callArrays,
                                    const ProgressCallback& progress) {
  const Session& session = request.session();
  LIC3D_TRY_ASSIGN(SessionInputs * inputs, inputsFor(request, std::move(callArrays)));
  LIC3D_TRY(checkViewScalarNames(session, inputs));
  LIC3D_TRY(openDevices(request));
  // What the renderer holds is counted as free: it is the request's own.
  if (!renderer_)
    LIC3D_TRY(checkRequestMemory(contexts_.front(), session, inputs->field.dims,
                                 {.frame = true,
                                  .timeSeries = inputs->series.has_value() && !request.options->cpu,
                                  .deviceCap = request.options->memoryBudget}));
  Result<RgbaImage> image = [&]() -> Result<RgbaImage> {
    LIC3D_TRY_ASSIGN(LicRenderer * renderer, rendererFor(request, *inputs));
    if (request.options->cpu) {
      LIC3D_TRY_ASSIGN(const ScalarVolume volume,
                       computeLicReference(inputs->field, inputs->noise, session.lic, 0, progress));
      LIC3D_TRY(renderer->setLicVolume(volume, session.lic));
    } else {
      LIC3D_TRY_ASSIGN([[maybe_unused]] const bool ran, renderer->updateLic(session.lic, progress));
    }
    const ViewParams& view = session.view;
    const ScalarsKey key{view.color, view.colorBy, view.opacityBy, opacityWeighted(view)};
    if (!scalarsKey_ || !(*scalarsKey_ == key)) {
      scalarsKey_.reset();
      LIC3D_TRY_ASSIGN(const ViewScalars scalars, loadViewScalars(session, *inputs));
      LIC3D_TRY(setViewScalars(*renderer, scalars));
      scalarsKey_ = key;
    }
    return renderer->render(session.lic, view);
  }();
  LIC3D_TRY(checkValidation());
  return image;
}

template <class Made, class Work>
Made Renderer::call(const char* command, const py::object& session, const py::object& progress,
                    const py::dict& params, Work work) {
  std::vector<PointScalars> arrays;
  const Request made = request(command, session, params, arrays);
  setThreadLimit(made.global().threads);
  std::size_t nonFinite = 0;
  Made result = take(runInterruptibly<Result<Made>>(
      [&](const ProgressCallback& report) {
        const std::lock_guard lock(mutex_);
        if (closed_) return Result<Made>(runtimeError("the lic3d.Renderer is closed"));
        nonFinite_ = 0;
        Result<Made> done = (this->*work)(made, std::move(arrays), report);
        nonFinite = nonFinite_;
        return done;
      },
      progress));
  warnNonFinite(nonFinite);
  return result;
}

py::array_t<float> Renderer::compute(const py::object& session, const py::object& progress,
                                     const py::dict& params) {
  ScalarVolume result =
      call<ScalarVolume>("compute", session, progress, params, &Renderer::licVolume);
  markHiddenVoxels(result);
  const Dims d = result.dims;
  return arrayOf(std::move(result.values), {d.z, d.y, d.x});
}

py::array_t<std::uint8_t> Renderer::render(const py::object& session, const py::object& progress,
                                           const py::dict& params) {
  RgbaImage result = call<RgbaImage>("render", session, progress, params, &Renderer::picture);
  return arrayOf(std::move(result.pixels), {result.height, result.width, 4});
}

void Renderer::dropRenderer() {
  if (renderer_) dispatchesBefore_ += renderer_->licDispatchCount();
  renderer_.reset();
}

Renderer::Made Renderer::made() const {
  const py::gil_scoped_release unlocked;
  const std::lock_guard lock(mutex_);
  return {.inputs = inputsMade_,
          .renderers = renderersMade_,
          .licDispatches = dispatchesBefore_ + (renderer_ ? renderer_->licDispatchCount() : 0)};
}

void Renderer::close() {
  const py::gil_scoped_release unlocked;
  const std::lock_guard lock(mutex_);
  closed_ = true;
  dropRenderer();
  inputs_.reset();
  inputsKey_.reset();
  contexts_.clear();
}

std::vector<std::string> Renderer::deviceNames() const {
  const std::lock_guard lock(mutex_);
  std::vector<std::string> names;
  for (const Context& context : contexts_) names.push_back(context.deviceInfo().name);
  return names;
}

void bindRenderer(py::module_& module) {
  py::class_<Renderer>(
      module, "Renderer",
      R"(Renderer(vectors=None, *, spacing=1.0, origin=0.0, noise=None, scalars=None, session=None, **params)

A field and its devices, kept between calls (docs/PYTHON.md). The devices are opened when the
Renderer is made; the pipelines, the field's textures, the LIC volume and the colour scalars
are kept while the calls leave them as they were: a sweep of view parameters (azimuth, look,
colormap, ...) draws the same LIC volume again, a sweep of LIC parameters (length, ...) makes
only the LIC again. The arguments are those of lic3d.compute and lic3d.render; params are the
parameters every call starts from, which a call's own override. scalars: a dict of names to
arrays (nz, ny, nx) on the vectors' grid that color_by= and opacity_by= can name. device= and
devices= choose the devices once: with devices='all', compute spreads a LIC too large for one
device over them, and render draws on the first. Use it in a with block, or call close().
Calls are made one at a time, with the GIL released.)")
      .def(py::init([](const py::object& vectors, const py::object& spacing,
                       const py::object& origin, const py::object& noise, const py::object& scalars,
                       const py::object& session, const py::kwargs& params) {
             return std::make_unique<Renderer>(vectors, spacing, origin, noise, scalars, session,
                                               params, true);
           }),
           py::arg("vectors") = py::none(), py::kw_only(), py::arg("spacing") = 1.0,
           py::arg("origin") = 0.0, py::arg("noise") = py::none(), py::arg("scalars") = py::none(),
           py::arg("session") = py::none())
      .def(
          "compute",
          [](Renderer& self, const py::object& session, const py::object& progress,
             const py::kwargs& params) { return self.compute(session, progress, params); },
          py::kw_only(), py::arg("session") = py::none(), py::arg("progress") = py::none(),
          "compute(*, session=None, progress=None, **params) -> numpy.ndarray\n\n"
          "The LIC volume as lic3d.compute makes it, with the Renderer's parameters and these.")
      .def(
          "render",
          [](Renderer& self, const py::object& session, const py::object& progress,
             const py::kwargs& params) { return self.render(session, progress, params); },
          py::kw_only(), py::arg("session") = py::none(), py::arg("progress") = py::none(),
          "render(*, session=None, progress=None, **params) -> numpy.ndarray\n\n"
          "The picture as lic3d.render makes it, with the Renderer's parameters and these.")
      .def("close", &Renderer::close,
           "close()\n\nGives the devices and what was made on them back; later calls raise "
           "RuntimeError. Waits for a call in flight.")
      .def_property_readonly("closed", &Renderer::closed)
      .def_property_readonly(
          "made",
          [](const Renderer& self) {
            const Renderer::Made made = self.made();
            py::dict counts;
            counts["inputs"] = made.inputs;
            counts["renderers"] = made.renderers;
            counts["lic_dispatches"] = made.licDispatches;
            return counts;
          },
          "What the Renderer made so far, counted: inputs (the field and noise made or "
          "uploaded), renderers (pipelines and textures on the first device) and lic_dispatches "
          "(dispatches of the LIC pass). A call that only changes the view adds none.")
      .def_property_readonly("device_names", &Renderer::deviceNames,
                             "The names of the devices the Renderer opened.")
      .def("__enter__", [](Renderer& self) -> Renderer& { return self; })
      .def("__exit__", [](Renderer& self, const py::args&) { self.close(); });
}

}  // namespace lic3d::python
