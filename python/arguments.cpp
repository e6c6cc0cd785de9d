// SPDX-License-Identifier: BSD-3-Clause
#include "python/arguments.h"

#include <pybind11/stl.h>

#include <CLI/CLI.hpp>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>

#include "core/parameter_ranges.h"
#include "core/text.h"
#include "gpu/device_choice.h"
#include "lic/derived_fields.h"
#include "loading/scalars.h"

namespace lic3d::python {
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

void take(const Result<void>& result) {
  if (!result) raise(result.error());
}

namespace {

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

// The flag of a keyword: length_scale is --length-scale.
std::string flagOf(std::string keyword) {
  for (char& c : keyword) c = c == '_' ? '-' : c;
  return "--" + keyword;
}

// The option of the command (or a global one) a keyword names, if it is a parameter.
CLI::Option* optionOf(const cli::CommandLine& line, CLI::App& command, const std::string& keyword) {
  const std::string flag = flagOf(keyword);
  if (notParameters().contains(flag)) return nullptr;
  CLI::Option* option = command.get_option_no_throw(flag);
  return option ? option : line.app->get_option_no_throw(flag);
}

}  // namespace

void checkKeywords(const py::dict& params, const std::string& caller) {
  const std::unique_ptr<cli::CommandLine> line = cli::makeCommandLine();
  for (const auto& [key, value] : params) {
    const std::string keyword = key.cast<std::string>();
    if (!optionOf(*line, *line->computeCommand, keyword) &&
        !optionOf(*line, *line->renderCommand, keyword))
      throw py::type_error(caller + " got an unexpected keyword argument '" + keyword +
                           "' (its parameters are the long options of `lic3d compute --help` "
                           "and `lic3d render --help` with underscores)");
  }
}

Request parseRequest(const std::string& command, const py::object& session,
                     const py::object& noiseFile, const py::dict& params, const py::dict& base) {
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
  // The base's parameters that this command has, then the call's over them.
  py::dict all;
  for (const auto& [key, value] : base)
    if (optionOf(line, sub, key.cast<std::string>())) all[key] = value;
  for (const auto& [key, value] : params) all[key] = value;
  for (const auto& [key, value] : all) {
    const std::string flag = flagOf(key.cast<std::string>());
    CLI::Option* option = optionOf(line, sub, key.cast<std::string>());
    if (!option)
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

namespace {

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

}  // namespace

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

std::vector<PointScalars> heldScalars(const py::object& scalars, py::dict& params) {
  std::vector<PointScalars> held;
  const auto hold = [&](const std::string& name, const py::handle& value, const std::string& what) {
    const auto floats =
        arrayOfNumbers<float>(py::reinterpret_borrow<py::object>(value), what.c_str());
    if (floats.ndim() != 3)
      throw py::value_error(what + ": expected the shape (nz, ny, nx), got " + shapeText(floats));
    PointScalars array;
    array.dims = gridOf(floats, what.c_str());
    array.name = name;
    array.values.assign(floats.data(), floats.data() + floats.size());
    for (PointScalars& before : held)
      if (before.name == name) {
        before = std::move(array);
        return;
      }
    held.push_back(std::move(array));
  };
  if (!scalars.is_none()) {
    if (!py::isinstance<py::dict>(scalars))
      throw py::type_error("scalars: expected a dict of names to arrays (nz, ny, nx), got a " +
                           typeName(scalars));
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(scalars)) {
      if (!py::isinstance<py::str>(key))
        throw py::type_error("scalars: expected names (str) as keys, got a " + typeName(key));
      const std::string name = key.cast<std::string>();
      if (name.empty() || derivedQuantity(name) || name.ends_with(".nrrd") ||
          name.ends_with(".nhdr"))
        throw py::value_error("scalars: '" + name +
                              "' names a quantity lic3d derives or a file; give another name");
      hold(name, value, "scalars['" + name + "']");
    }
  }
  for (const char* keyword : {"color_by", "opacity_by"}) {
    if (!params.contains(keyword)) continue;
    const py::object value = params[keyword];
    if (!py::isinstance<py::array>(value) || py::reinterpret_borrow<py::array>(value).ndim() == 0)
      continue;
    hold(keyword, value, keyword);
    params[keyword] = keyword;
  }
  return held;
}

// The inputs of a request: the arrays given, else the session's field (analytic or a file).
void checkFieldChoice(Request& request, bool vectorsGiven, bool noiseArray) {
  Session& session = request.session();
  if (session.twoD) throw py::value_error("the session is a 2D one (mode 2d)");
  if (!vectorsGiven && noiseArray)
    throw py::value_error(
        "noise: an array of noise goes with vectors on its grid; with field=... give the noise "
        "as a file (noise='n.nrrd') or choose it with seed, seed_noise or seed_fraction");
  if (!vectorsGiven) return;
  for (const char* flag : {"--field", "--grid", "--array", "--time", "--time-steps"})
    if (request.given.contains(flag))
      throw py::value_error(std::string(flag) + " chooses the field: give it or vectors, not both");
  session.field = {.field = "array", .resolution = session.field.resolution};
}

InputOptions inputOptions(const Request& request) {
  // An analytic field is made on the device where the command line makes it there, so that
  // both give the same numbers.
  const Session& session = request.session();
  const bool compute = request.options == &request.line->compute;
  const bool onDevice = !request.options->cpu && (compute || !viewDerivesFromField(session.view));
  return {.gridGiven = request.given.contains("--grid"),
          .analyticTimeSteps = session.timeSteps,
          .fieldOnDevice = onDevice};
}

// With validation on, a message is an error even when the work succeeded.
Result<void> checkValidation(const Context& context) {
  if (context.validationEnabled() && context.validationMessageCount() > 0)
    return Error{ErrorKind::Runtime,
                 std::to_string(context.validationMessageCount()) + " validation message(s)"};
  return {};
}

namespace {

Result<Context> openDevice(const cli::GlobalOptions& global) {
  return Context::create({.validation = global.validation, .device = global.device});
}

}  // namespace

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

void warnNonFinite(std::size_t vectors) {
  if (vectors == 0) return;
  const std::string message = std::to_string(vectors) +
                              " vector(s) with a NaN or infinite component were read as zero "
                              "(streamlines stop there)";
  if (PyErr_WarnEx(PyExc_RuntimeWarning, message.c_str(), 1) != 0) throw py::error_already_set();
}

}  // namespace lic3d::python
