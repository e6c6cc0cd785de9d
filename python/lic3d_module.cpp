// SPDX-License-Identifier: BSD-3-Clause
// The Python module lic3d (docs/PYTHON.md): LIC volumes and pictures of numpy arrays, made by the
// engine the command line uses. Parameters are the command line's long options with underscores
// (length=30 is --length 30), parsed and checked by the same code, so a refused value raises
// ValueError with the message `lic3d` prints.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <CLI/CLI.hpp>
#include <array>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <set>
#include <stop_token>
#include <string>
#include <thread>
#include <vector>

#include "core/parallel.h"
#include "core/parameter_ranges.h"
#include "core/text.h"
#include "gpu/device_choice.h"
#include "gpu/vulkan_context.h"
#include "jobs/bricks.h"
#include "lic/lic_reference.h"
#include "loading/scalars.h"
#include "loading/session_inputs.h"
#include "options/command_line.h"
#include "render/lic_renderer.h"

namespace py = pybind11;

namespace lic3d::python {
namespace {

// An engine error as a Python exception: bad input ValueError, not enough memory MemoryError,
// anything else (no device, a GPU failure) RuntimeError.
[[noreturn]] void raise(const Error& error) {
  const std::string message = cutMessage(cli::messageWithFlags(error), 1000);
  if (error.kind == ErrorKind::InvalidInput) throw py::value_error(message);
  if (error.kind == ErrorKind::ResourceLimit) {
    PyErr_SetString(PyExc_MemoryError, message.c_str());
    throw py::error_already_set();
  }
  throw std::runtime_error(message);
}

template <class T>
T take(Result<T> result) {
  if (!result) raise(result.error());
  return std::move(*result);
}

void take(const Result<void>& result) {
  if (!result) raise(result.error());
}

// The command line's flags that are not parameters of a LIC volume or picture: outputs,
// animations and what only a terminal shows.
const std::set<std::string>& notParameters() {
  static const std::set<std::string> flags = {
      "--output", "--session",   "--help",          "--version",
      "--quiet",  "--timings",   "--rgba-volume",   "--slice",
      "--frames", "--turntable", "--animate-bias",  "--animate-time",
      "--video",  "--fps",       "--skip-existing", "--time-range"};
  return flags;
}

// The type of `value` for messages: "list", "numpy.ndarray".
std::string typeName(const py::handle& value) {
  const py::handle type = py::type::handle_of(value);
  const std::string module = py::str(type.attr("__module__")).cast<std::string>();
  const std::string name = py::str(type.attr("__qualname__")).cast<std::string>();
  return module == "builtins" ? name : module + "." + name;
}

// A number: Python's or numpy's (a numpy scalar, a 0-d array), not a bool.
bool isNumber(const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return false;
  if (py::isinstance<py::array>(value)) return py::reinterpret_borrow<py::array>(value).ndim() == 0;
  return PyNumber_Check(value.ptr()) != 0 && !py::isinstance<py::str>(value) &&
         !PySequence_Check(value.ptr());
}

// One value as the command line takes it: True/False as on/off, a string or number as its text.
// Nothing else: `keyword` names it when refused.
std::string scalarText(const py::handle& value, const std::string& keyword, const char* expected) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "on" : "off";
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (isNumber(value)) {
    // A whole number as one, so that 5.0 or numpy.float32(5) is a length as 5 is.
    if (!PyLong_Check(value.ptr()) && !PyObject_HasAttrString(value.ptr(), "__index__")) {
      const double number = PyFloat_AsDouble(value.ptr());
      if (number == -1.0 && PyErr_Occurred()) throw py::error_already_set();
      if (std::isfinite(number) && std::trunc(number) == number && std::abs(number) < 0x1p53)
        return std::to_string(static_cast<long long>(number));
    }
    return py::str(value).cast<std::string>();
  }
  throw py::type_error(keyword + ": expected " + expected + ", got a " + typeName(value));
}

// A keyword's value as the command line takes it: a number, a string or True/False, or a flat
// sequence of them joined with commas. A value lic3d takes is never nested, so a nested or
// self-containing list is refused here instead of being followed.
std::string valueText(const py::handle& value, const std::string& keyword) {
  constexpr const char* kExpected =
      "a number, a string, True/False or a flat sequence of numbers or strings";
  const bool sequence = !py::isinstance<py::str>(value) && !py::isinstance<py::bytes>(value) &&
                        !isNumber(value) &&
                        (py::isinstance<py::sequence>(value) || py::isinstance<py::array>(value));
  if (!sequence) return scalarText(value, keyword, kExpected);
  std::string text;
  for (const py::handle item : py::iter(value)) {
    const bool nested = !py::isinstance<py::str>(item) && !isNumber(item) &&
                        (py::isinstance<py::sequence>(item) || py::isinstance<py::array>(item));
    if (nested)
      throw py::type_error(keyword + ": expected " + kExpected + ", got a " + typeName(value) +
                           " holding a " + typeName(item));
    text += (text.empty() ? "" : ",") + scalarText(item, keyword, kExpected);
  }
  return text;
}

// A file's path (a str or os.PathLike) as the flag `keyword` takes it.
std::string pathText(const py::object& value, const std::string& keyword, const char* expected) {
  if (!py::isinstance<py::str>(value) && !py::hasattr(value, "__fspath__"))
    throw py::type_error(keyword + ": expected " + expected + ", got a " + typeName(value));
  const py::object path = py::module_::import("os").attr("fspath")(value);
  if (!py::isinstance<py::str>(path))
    throw py::type_error(keyword + ": expected " + expected + ", got a bytes path");
  return path.cast<std::string>();
}

// A parsed request: the command line of `compute` or `render`, filled from keyword arguments.
struct Request {
  std::unique_ptr<cli::CommandLine> line;
  cli::ComputeOptions* options = nullptr;
  std::set<std::string> given;  // the flags given

  Session& session() const { return options->inputs.session; }
  const cli::GlobalOptions& global() const { return line->global; }
};

Request parseRequest(const std::string& command, const py::object& session,
                     const py::object& noiseFile, const py::kwargs& params) {
  Request request;
  request.line = cli::makeCommandLine();
  cli::CommandLine& line = *request.line;
  const bool render = command == "render";
  CLI::App& sub = render ? *line.renderCommand : *line.computeCommand;
  request.options = render ? &line.render : &line.compute;

  std::vector<std::string> args = {"lic3d", command};
  if (py::isinstance<py::dict>(session)) {
    // A dict is a session as JSON holds it (lic3d.session() makes one).
    const auto text = py::module_::import("json").attr("dumps")(session).cast<std::string>();
    request.session() = take(sessionFromJson(text, "session"));
    request.options->inputs.sessionFile = "session";  // no default look over it
  } else if (!session.is_none()) {
    // A file: JSON or PNG.
    args.push_back("--session=" +
                   pathText(session, "session", "a dict, or a session file's path (JSON or PNG)"));
  }
  if (!noiseFile.is_none())
    args.push_back("--noise=" +
                   pathText(noiseFile, "noise", "an array (nz, ny, nx) or a noise file's path"));
  for (const auto& [key, value] : params) {
    std::string name = key.cast<std::string>();
    for (char& c : name) c = c == '_' ? '-' : c;
    const std::string flag = "--" + name;
    CLI::Option* option = sub.get_option_no_throw(flag);
    if (!option) option = line.app->get_option_no_throw(flag);
    if (!option || notParameters().contains(flag))
      throw py::type_error("lic3d." + command + "() got an unexpected keyword argument '" +
                           key.cast<std::string>() +
                           "' (its parameters are the long options of `lic3d " + command +
                           " --help` with underscores)");
    if (value.is_none()) continue;
    request.given.insert(flag);
    // A flag takes no value: True gives it, False leaves it out.
    if (option->get_type_size_max() == 0) {
      if (!py::isinstance<py::bool_>(value))
        throw py::value_error(flag + " is a switch: give True or False");
      if (value.cast<bool>()) args.push_back(flag);
      continue;
    }
    args.push_back(flag + "=" + valueText(value, key.cast<std::string>()));
  }
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  Result<void> parsed = cli::parseArguments(*line.app, static_cast<int>(argv.size()), argv.data(),
                                            {&request.options->inputs});
  if (!parsed) raise(parsed.error());
  take(cli::finishCommand(line));
  return request;
}

// A finite number (Python's or numpy's), else TypeError or ValueError naming `what`.
double numberOf(const py::handle& value, const char* what) {
  const std::string expected = std::string(what) + ": expected 3 numbers (x, y, z) or one";
  if (!isNumber(value)) throw py::type_error(expected + ", got a " + typeName(value));
  const double number = PyFloat_AsDouble(value.ptr());
  if (number == -1.0 && PyErr_Occurred()) {
    const py::error_already_set error;  // an int beyond a double: OverflowError
    throw py::value_error(expected + ", got a number beyond a double");
  }
  if (!std::isfinite(number))
    throw py::value_error(expected + " that are finite, got " + formatDouble(number));
  return number;
}

std::array<double, 3> triple(const py::object& value, const char* what) {
  if (isNumber(value)) {
    const double v = numberOf(value, what);
    return {v, v, v};
  }
  const bool sequence = !py::isinstance<py::str>(value) && !py::isinstance<py::bytes>(value) &&
                        (py::isinstance<py::sequence>(value) || py::isinstance<py::array>(value));
  if (!sequence)
    throw py::type_error(std::string(what) + ": expected 3 numbers (x, y, z) or one, got a " +
                         typeName(value));
  std::vector<double> items;
  for (const py::handle item : py::iter(value)) {
    if (items.size() == 3) break;
    items.push_back(numberOf(item, what));
  }
  if (items.size() != 3 || py::len(value) != 3)
    throw py::value_error(std::string(what) + ": expected 3 numbers (x, y, z) or one, got " +
                          std::to_string(py::len(value)));
  return {items[0], items[1], items[2]};
}

// `value` as a C-contiguous array of T. numpy's own MemoryError (a huge broadcast array made
// whole) stays a MemoryError; anything else that is no array of numbers is a ValueError.
template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> arrayOfNumbers(const py::object& value,
                                                                         const char* what) {
  try {
    return py::array_t<T, py::array::c_style | py::array::forcecast>(value);
  } catch (py::error_already_set& error) {
    if (error.matches(PyExc_MemoryError)) throw;
    throw py::value_error(std::string(what) + ": expected an array of numbers (" +
                          cutMessage(error.what(), 200) + ")");
  }
}

std::string shapeText(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < array.ndim(); ++d)
    text += (d ? ", " : "") + std::to_string(array.shape(d));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

Dims gridOf(const py::array& array, const char* what) {
  const Dims dims(static_cast<int>(array.shape(2)), static_cast<int>(array.shape(1)),
                  static_cast<int>(array.shape(0)));
  for (int a = 0; a < 3; ++a)
    if (!ranges::kGrid.contains(static_cast<double>(array.shape(2 - a))))
      throw py::value_error(std::string(what) + ": each of nz, ny, nx must be in " +
                            ranges::kGrid.text() + ", got the shape " + shapeText(array));
  return dims;
}

// (nz, ny, nx, 3) numbers, x fastest as VTK and NRRD store them, as the engine's field.
VectorField fieldOf(const py::array& vectors, const py::object& spacing, const py::object& origin) {
  const auto floats = arrayOfNumbers<float>(vectors, "vectors");
  if (floats.ndim() != 4 || floats.shape(3) != 3)
    throw py::value_error("vectors: expected the shape (nz, ny, nx, 3), got " + shapeText(floats));
  VectorField field;
  field.dims = gridOf(floats, "vectors");
  const auto s = triple(spacing, "spacing");
  const auto o = triple(origin, "origin");
  field.geometry = {{s[0], s[1], s[2]}, {o[0], o[1], o[2]}};
  field.vectors.resize(voxelCount(field.dims));
  std::memcpy(field.vectors.data(), floats.data(), field.vectors.size() * sizeof(glm::vec3));
  return field;
}

// (nz, ny, nx) of uint8, uint16 or float32, read as the engine reads noise files.
NoiseVolume noiseOf(const py::array& noise) {
  NoiseVolume volume;
  const py::dtype type = noise.dtype();
  if (type.is(py::dtype::of<std::uint8_t>())) {
    volume.type = NoiseType::UInt8;
  } else if (type.is(py::dtype::of<std::uint16_t>())) {
    volume.type = NoiseType::UInt16;
  } else if (type.is(py::dtype::of<float>())) {
    volume.type = NoiseType::Float32;
  } else {
    throw py::value_error("noise: expected uint8, uint16 or float32 values, got " +
                          type.attr("name").cast<std::string>());
  }
  if (noise.ndim() != 3)
    throw py::value_error("noise: expected the shape (nz, ny, nx), got " + shapeText(noise));
  volume.dims = gridOf(noise, "noise");
  // numpy's copy raises its own MemoryError where the array cannot be made contiguous.
  const auto contiguous = py::reinterpret_borrow<py::array>(
      py::module_::import("numpy").attr("ascontiguousarray")(noise));
  const auto* bytes = static_cast<const std::uint8_t*>(contiguous.data());
  volume.bytes.assign(bytes, bytes + contiguous.nbytes());
  return volume;
}

// The inputs of a request: the arrays given, else the session's field (analytic or a file).
SessionInputs inputsOf(Request& request, const py::object& vectors, const py::object& spacing,
                       const py::object& origin, const py::object& noise) {
  Session& session = request.session();
  if (session.twoD) throw py::value_error("the session is a 2D one (mode 2d)");
  if (vectors.is_none() && py::isinstance<py::array>(noise))
    throw py::value_error(
        "noise: an array of noise goes with vectors on its grid; with field=... give the noise "
        "as a file (noise='n.nrrd') or choose it with seed, seed_noise or seed_fraction");
  if (vectors.is_none()) {
    // An analytic field is made on the device where the command line makes it there, so that
    // both give the same numbers.
    const bool compute = request.options == &request.line->compute;
    const bool onDevice = !request.options->cpu && (compute || !viewDerivesFromField(session.view));
    return take(loadSessionInputs(session, {.gridGiven = request.given.contains("--grid"),
                                            .analyticTimeSteps = session.timeSteps,
                                            .fieldOnDevice = onDevice}));
  }
  for (const char* flag : {"--field", "--grid", "--array", "--time", "--time-steps"})
    if (request.given.contains(flag))
      throw py::value_error(std::string(flag) + " chooses the field: give it or vectors, not both");
  session.field = {.field = "array", .resolution = session.field.resolution};
  std::optional<NoiseVolume> noiseVolume;
  if (py::isinstance<py::array>(noise)) noiseVolume = noiseOf(noise);
  return take(sessionInputsOf(session, fieldOf(vectors, spacing, origin), std::move(noiseVolume),
                              "vectors"));
}

// With validation on, a message is an error even when the work succeeded.
Result<void> checkValidation(const Context& context) {
  if (context.validationEnabled() && context.validationMessageCount() > 0)
    return Error{ErrorKind::Runtime,
                 std::to_string(context.validationMessageCount()) + " validation message(s)"};
  return {};
}

Result<Context> openDevice(const cli::GlobalOptions& global) {
  return Context::create({.validation = global.validation, .device = global.device});
}

// devices=: the contexts of the devices named, as `lic3d compute --devices` opens them.
Result<std::vector<Context>> openDevices(const cli::GlobalOptions& global,
                                         const std::string& devices) {
  std::vector<Context> contexts;
  if (devices.empty()) {
    LIC3D_TRY_ASSIGN(Context context, openDevice(global));
    contexts.push_back(std::move(context));
    return contexts;
  }
  LIC3D_TRY_ASSIGN(const std::vector<DeviceInfo> listed, listDevices());
  Result<std::vector<int>> chosen = chooseDevices(listed, devices);
  if (!chosen) return inputError("--" + chosen.error().message);
  for (const int index : *chosen) {
    cli::GlobalOptions one = global;
    one.device = std::to_string(index);
    LIC3D_TRY_ASSIGN(Context context, openDevice(one));
    contexts.push_back(std::move(context));
  }
  return contexts;
}

// What the command line refuses of devices=, before any work.
void checkDevices(const Request& request, bool render) {
  const std::string& devices = request.options->devices;
  if (devices.empty()) return;
  if (request.options->cpu)
    throw py::value_error("--devices " + devices + ": --cpu computes on the CPU, not on devices");
  if (!request.global().device.empty())
    throw py::value_error("--device " + request.global().device + " --devices " + devices +
                          ": give one device (--device) or several (--devices), not both");
  if (render)
    throw py::value_error("--devices " + devices +
                          ": lic3d.render draws on one device (device=...); lic3d.compute "
                          "spreads a LIC volume over several");
}

// The LIC volume, on the device the options choose or (cpu) the CPU reference. No Python here:
// it runs with the GIL released.
Result<ScalarVolume> licVolume(const Request& request, SessionInputs& inputs,
                               const ProgressCallback& progress) {
  const Session& session = request.session();
  if (request.options->cpu) {
    if (inputs.series) {
      LIC3D_TRY_ASSIGN(inputs.field, hostFieldAt(inputs, session, session.time));
    }
    return computeLicReference(inputs.field, inputs.noise, session.lic, 0, progress);
  }
  LIC3D_TRY_ASSIGN(const std::vector<Context> contexts,
                   openDevices(request.global(), request.options->devices));
  std::vector<const Context*> devices;
  for (const Context& context : contexts) devices.push_back(&context);
  // In one piece when it fits the device (or memory_budget), else in bricks spread over the
  // devices, as lic3d compute.
  Result<LicVolumeRun> run = computeLicVolume(
      devices, session, inputs, {.deviceCap = request.options->memoryBudget}, progress);
  for (const Context& context : contexts) LIC3D_TRY(checkValidation(context));
  if (!run) return run.error();
  return std::move(run->volume);
}

// The picture of the session's view, as `lic3d render` makes it.
Result<RgbaImage> picture(const Request& request, SessionInputs& inputs,
                          const ProgressCallback& progress) {
  const Session& session = request.session();
  LIC3D_TRY(checkViewScalarNames(session, &inputs));
  LIC3D_TRY_ASSIGN(Context context, openDevice(request.global()));
  LIC3D_TRY(checkRequestMemory(context, session, inputs.field.dims,
                               {.frame = true,
                                .timeSeries = inputs.series.has_value() && !request.options->cpu,
                                .deviceCap = request.options->memoryBudget}));
  Result<RgbaImage> image = [&]() -> Result<RgbaImage> {
    LIC3D_TRY_ASSIGN(LicRenderer renderer, LicRenderer::create(context, {session.precision}));
    LIC3D_TRY(moveToTime(inputs, session, session.time, renderer, true, request.options->cpu));
    if (request.options->cpu) {
      LIC3D_TRY_ASSIGN(const ScalarVolume volume,
                       computeLicReference(inputs.field, inputs.noise, session.lic, 0, progress));
      LIC3D_TRY(renderer.setLicVolume(volume, session.lic));
    } else {
      LIC3D_TRY_ASSIGN([[maybe_unused]] const bool ran, renderer.updateLic(session.lic, progress));
    }
    LIC3D_TRY_ASSIGN(const ViewScalars scalars, loadViewScalars(session, inputs));
    LIC3D_TRY(setViewScalars(renderer, scalars));
    return renderer.render(session.lic, session.view);
  }();
  LIC3D_TRY(checkValidation(context));
  return image;
}

void warnNonFinite(const SessionInputs& inputs) {
  if (inputs.info.nonFiniteVectors == 0) return;
  const std::string message = std::to_string(inputs.info.nonFiniteVectors) +
                              " vector(s) with a NaN or infinite component were read as zero "
                              "(streamlines stop there)";
  if (PyErr_WarnEx(PyExc_RuntimeWarning, message.c_str(), 1) != 0) throw py::error_already_set();
}

// A vector's values as a numpy array that owns them.
template <class T>
py::array_t<T> arrayOf(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  const py::capsule release(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(std::move(shape), owned->data(), release);
}

// What `work` made on a thread of its own, waited for with the GIL released. Its progress goes
// to `report` (a callable or None); after each report, and every 50 ms in between, Python's
// signal handlers run. On Ctrl-C (KeyboardInterrupt), or an exception from `report`, the work is
// asked to stop, which it does at the end of its unit of work in flight (a slab of the GPU pass,
// a row of the CPU reference, a brick), and the exception is raised once it has: no work is left
// running, and the module can be used at once.
template <class Made, class Work>
Made runInterruptibly(Work work, const py::object& report) {
  std::mutex mutex;
  std::condition_variable changed;
  std::optional<Made> made;
  std::uint64_t reports = 0;  // progress reports made
  std::uint64_t checked = 0;  // those after which the signal handlers ran
  std::stop_source stop;
  std::optional<py::error_already_set> reportFailed;  // touched with the GIL held
  const auto onProgress = [&](double fraction) {
    if (report.is_none()) return;
    {
      const py::gil_scoped_acquire locked;
      try {
        if (!reportFailed) report(fraction);
      } catch (py::error_already_set& e) {
        reportFailed = std::move(e);
        stop.request_stop();
      }
    }
    // The work goes on once a Ctrl-C made meanwhile (by `report` too) has been seen, so that it
    // stops here.
    std::unique_lock lock(mutex);
    const std::uint64_t number = ++reports;
    changed.notify_all();
    changed.wait(lock, [&] { return checked >= number || stop.stop_requested(); });
  };
  std::thread thread([&] {
    Made result = Error{};
    try {
      result = work(ProgressCallback(onProgress, stop.get_token()));
    } catch (const std::bad_alloc&) {
      result = Error{ErrorKind::ResourceLimit, "not enough host memory"};
    } catch (const std::exception& e) {
      result = Error{ErrorKind::Runtime, e.what()};
    }
    {
      const std::lock_guard lock(mutex);
      made = std::move(result);
    }
    changed.notify_all();
  });
  const auto join = [&] {
    const py::gil_scoped_release unlocked;
    thread.join();
  };
  try {
    for (;;) {
      std::uint64_t seen = 0;
      {
        const py::gil_scoped_release unlocked;
        std::unique_lock lock(mutex);
        changed.wait_for(lock, std::chrono::milliseconds(50),
                         [&] { return made.has_value() || reports > checked; });
        if (made) break;
        seen = reports;
      }
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      {
        const std::lock_guard lock(mutex);
        checked = seen;
      }
      changed.notify_all();
    }
  } catch (...) {
    {
      const std::lock_guard lock(mutex);
      stop.request_stop();
    }
    changed.notify_all();
    join();
    throw;
  }
  join();
  if (reportFailed) throw *reportFailed;
  return std::move(*made);
}

// A request of `command` made with the GIL released by `work` (licVolume or picture), its result
// taken (an error raised), and the inputs' non-finite vectors warned of.
template <class Work>
auto runRequest(const char* command, const py::object& vectors, const py::object& spacing,
                const py::object& origin, const py::object& noise, const py::object& session,
                const py::object& progress, const py::kwargs& params, Work work) {
  const bool noiseArray = py::isinstance<py::array>(noise);
  Request request = parseRequest(command, session, noiseArray ? py::none() : noise, params);
  checkDevices(request, std::string_view(command) == "render");
  SessionInputs inputs = inputsOf(request, vectors, spacing, origin, noise);
  setThreadLimit(request.global().threads);
  using Made = decltype(work(request, inputs, ProgressCallback()));
  auto result = take(runInterruptibly<Made>(
      [&](const ProgressCallback& report) { return work(request, inputs, report); }, progress));
  warnNonFinite(inputs);
  return result;
}

py::array_t<float> compute(const py::object& vectors, const py::object& spacing,
                           const py::object& origin, const py::object& noise,
                           const py::object& session, const py::object& progress,
                           const py::kwargs& params) {
  ScalarVolume result =
      runRequest("compute", vectors, spacing, origin, noise, session, progress, params, licVolume);
  markHiddenVoxels(result);
  const Dims d = result.dims;
  return arrayOf(std::move(result.values), {d.z, d.y, d.x});
}

py::array_t<std::uint8_t> render(const py::object& vectors, const py::object& spacing,
                                 const py::object& origin, const py::object& noise,
                                 const py::object& session, const py::object& progress,
                                 const py::kwargs& params) {
  RgbaImage result =
      runRequest("render", vectors, spacing, origin, noise, session, progress, params, picture);
  return arrayOf(std::move(result.pixels), {result.height, result.width, 4});
}

// The session the parameters make, as a dict (the JSON a saved session or a PNG holds).
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
             py::arg("session") = py::none(), py::arg("progress") = py::none(),
             "compute(vectors=None, *, spacing=1.0, origin=0.0, noise=None, "
             "session=None, progress=None, **params) -> numpy.ndarray\n\n"
             "The LIC volume of `vectors` (numbers shaped (nz, ny, nx, 3), x fastest) as "
             "float32 shaped (nz, ny, nx), as `lic3d compute` writes it. Without vectors, "
             "the field of field=... (an analytic field or a file). noise: an array "
             "(nz, ny, nx) of uint8, uint16 or float32 on the LIC grid, or a noise file; "
             "default seeded white noise. session: a dict (lic3d.session()) or a session "
             "file (JSON or a PNG lic3d wrote) the parameters then override. "
             "device='' picks as `lic3d --device` does, devices='all' spreads the LIC over "
             "several as `lic3d compute --devices` does; cpu=True uses the CPU reference. "
             "progress: a callable that gets the finished fraction of the LIC now and then "
             "(from another thread). The GIL is released while the LIC is made; Ctrl-C, or an "
             "exception from progress, stops the work at its next slab or brick and is raised.");
  module.def("render", &render, py::arg("vectors") = py::none(), py::kw_only(),
             py::arg("spacing") = 1.0, py::arg("origin") = 0.0, py::arg("noise") = py::none(),
             py::arg("session") = py::none(), py::arg("progress") = py::none(),
             "render(vectors=None, *, spacing=1.0, origin=0.0, noise=None, "
             "session=None, progress=None, **params) -> numpy.ndarray\n\n"
             "The picture `lic3d render` makes, as uint8 RGBA shaped (height, width, 4), "
             "rows top to bottom. Arguments as for compute, plus the view parameters "
             "(look, size, azimuth, elevation, colormap, ...).");
  module.def("session", &sessionDict, py::arg("session") = py::none(),
             "session(session=None, **params) -> dict\n\n"
             "The whole session the parameters make (over `session`, a dict or file), as the "
             "dict that compute and render take and session files hold.");
  module.def("devices", &devices,
             "devices() -> list of dict\n\nThe Vulkan devices lic3d can use: index, name, type "
             "(device=index or a part of the name chooses one).");
}
