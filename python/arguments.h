// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The Python module's arguments (docs/PYTHON.md): keyword arguments as the command line's flags,
// numpy arrays as the engine's field, noise and scalars, engine errors as Python exceptions, and
// work run with the GIL released.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "gpu/vulkan_context.h"
#include "loading/session_inputs.h"
#include "options/command_line.h"

namespace lic3d::python {

namespace py = pybind11;

// An engine error as a Python exception: bad input ValueError, not enough memory MemoryError,
// anything else (no device, a GPU failure) RuntimeError.
[[noreturn]] void raise(const Error& error);

template <class T>
T take(Result<T> result) {
  if (!result) raise(result.error());
  return std::move(*result);
}
void take(const Result<void>& result);

// A parsed request: the command line of `compute` or `render`, filled from keyword arguments.
struct Request {
  std::unique_ptr<cli::CommandLine> line;
  cli::ComputeOptions* options = nullptr;
  std::set<std::string> given;  // the flags given

  Session& session() const { return options->inputs.session; }
  const cli::GlobalOptions& global() const { return line->global; }
};

// The command line of `command` ("compute" or "render") that the keyword arguments make: those
// of `base` (a Renderer's own) that the command has, then `params` over them. `session`: a dict,
// a session file (JSON or PNG) or None; `noiseFile` a noise file or None. TypeError for a keyword
// that is no parameter, ValueError with the command line's message for a refused value.
Request parseRequest(const std::string& command, const py::object& session,
                     const py::object& noiseFile, const py::dict& params,
                     const py::dict& base = py::dict());

// TypeError naming `caller` for a keyword that is a parameter of neither compute nor render.
void checkKeywords(const py::dict& params, const std::string& caller);

// (nz, ny, nx, 3) numbers, x fastest as VTK and NRRD store them, as the engine's field.
VectorField fieldOf(const py::array& vectors, const py::object& spacing, const py::object& origin);
// (nz, ny, nx) of uint8, uint16 or float32, read as the engine reads noise files.
NoiseVolume noiseOf(const py::array& noise);

// Scalar arrays held in memory (SessionInputs::arrays): `scalars`, a dict of names to arrays
// (nz, ny, nx), and color_by= or opacity_by= given an array, which `params` then names by its
// keyword ("color_by", "opacity_by").
std::vector<PointScalars> heldScalars(const py::object& scalars, py::dict& params);

// The request's field, checked with the GIL held: the vectors given (session.field then names
// "array") or field=..., not both; a noise array goes with vectors.
void checkFieldChoice(Request& request, bool vectorsGiven, bool noiseArray);
// How the inputs of a field=... request are made (loadSessionInputs).
InputOptions inputOptions(const Request& request);

// With validation on, a message is an error even when the work succeeded.
Result<void> checkValidation(const Context& context);

// devices=: the contexts of the devices named, as `lic3d compute --devices` opens them; none
// named: the one of --device.
Result<std::vector<Context>> openDevices(const cli::GlobalOptions& global,
                                         const std::string& devices);

// RuntimeWarning for `vectors` read as zero (SessionInputs::info.nonFiniteVectors).
void warnNonFinite(std::size_t vectors);

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

}  // namespace lic3d::python
