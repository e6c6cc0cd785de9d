// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// lic3d.Renderer (docs/PYTHON.md): a field, its devices and what was made of it, kept between
// calls. The devices are opened once; the renderer's pipelines, the field's textures, the LIC
// volume and the scalars colour follows are kept while the calls leave them as they were, so a
// sweep of view parameters draws the same LIC volume again, and a sweep of LIC parameters makes
// only the LIC again. lic3d.compute and lic3d.render are a Renderer used once.
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "python/arguments.h"
#include "render/lic_renderer.h"

namespace lic3d::python {

class Renderer {
 public:
  // The field: `vectors` (with spacing, origin, noise and scalars) or the session's field=...;
  // `session` and `params` are the parameters every call starts from. `keep`: a Renderer of its
  // own (devices opened now, the vectors kept for later inputs); false for one call.
  Renderer(const py::object& vectors, const py::object& spacing, const py::object& origin,
           const py::object& noise, const py::object& scalars, const py::object& session,
           const py::dict& params, bool keep);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // The LIC volume as float32 (nz, ny, nx), NaN where hidden, as lic3d.compute makes it.
  py::array_t<float> compute(const py::object& session, const py::object& progress,
                             const py::dict& params);
  // The picture as uint8 RGBA (height, width, 4), as lic3d.render makes it.
  py::array_t<std::uint8_t> render(const py::object& session, const py::object& progress,
                                   const py::dict& params);
  // Gives the devices back; later calls raise RuntimeError. Waits for a call in flight.
  void close();
  bool closed() const { return closed_; }
  // The names of the devices opened (none before the first device is needed).
  std::vector<std::string> deviceNames() const;
  // What was made so far: the inputs, the renderers on the first device, and the dispatches of
  // the LIC pass they ran (how a caller sees what a call made again).
  struct Made {
    std::uint64_t inputs = 0, renderers = 0, licDispatches = 0;
  };
  Made made() const;

 private:
  // What a set of inputs was made from: the same key, the same inputs.
  struct InputsKey {
    Session session;  // its field, noise and time steps
    InputOptions options;
    bool cpu = false;
    bool operator==(const InputsKey& other) const;
  };
  // What the colour and opacity scalars were loaded for.
  struct ScalarsKey {
    ColorMode color = ColorMode::None;
    std::string colorBy, opacityBy;
    bool weighted = false;
    bool operator==(const ScalarsKey&) const = default;
  };

  Request request(const char* command, const py::object& session, const py::dict& params,
                  std::vector<PointScalars>& callArrays) const;
  // The inputs of `request` (made again only where its key changed), the call's arrays beside
  // the Renderer's. With the mutex held.
  Result<SessionInputs*> inputsFor(const Request& request, std::vector<PointScalars>&& callArrays);
  Result<void> openDevices(const Request& request);
  // The renderer on the first device, holding the inputs at the session's time.
  Result<LicRenderer*> rendererFor(const Request& request, SessionInputs& inputs);
  // A call of `command`: its request parsed with the GIL held, then `work` (&Renderer::licVolume
  // or &Renderer::picture) on a thread of its own
  // with the GIL released and the mutex held (calls take turns); its error raised, and the
  // vectors of new inputs read as zero warned of.
  template <class Made, class Work>
  Made call(const char* command, const py::object& session, const py::object& progress,
            const py::dict& params, Work work);
  Result<ScalarVolume> licVolume(const Request& request, std::vector<PointScalars>&& callArrays,
                                 const ProgressCallback& progress);
  Result<RgbaImage> picture(const Request& request, std::vector<PointScalars>&& callArrays,
                            const ProgressCallback& progress);
  Result<void> checkValidation() const;
  void dropRenderer();
  void checkOpen() const;

  bool keep_;
  // The field given as arrays (else the session's field=...).
  std::optional<VectorField> vectors_;
  std::optional<NoiseVolume> noise_;
  py::object noiseFile_;
  std::vector<PointScalars> arrays_;
  py::object session_;
  py::dict params_;

  mutable std::mutex mutex_;  // one call at a time, taken with the GIL released
  bool closed_ = false;
  std::string devicesChosen_;  // the device= and devices= the contexts were opened for
  std::vector<Context> contexts_;
  std::optional<LicRenderer> renderer_;  // on contexts_[0]; made before it is destroyed
  FieldPrecision rendererPrecision_ = FieldPrecision::Auto;
  std::optional<SessionInputs> inputs_;
  std::optional<InputsKey> inputsKey_;
  std::uint64_t inputsMade_ = 0;      // inputs made so far: which ones the renderer holds
  std::uint64_t rendererInputs_ = 0;  // the inputs_ the renderer was given (0: none)
  std::optional<ScalarsKey> scalarsKey_;
  std::uint64_t scalarsInputs_ = 0;  // the inputs_ the scalars were loaded from
  std::size_t nonFinite_ = 0;        // of inputs made in the call under way
  bool callArraysHeld_ = false;      // inputs_ holds arrays a call gave
  std::uint64_t renderersMade_ = 0;
  std::uint64_t dispatchesBefore_ = 0;  // of the renderers made before renderer_
};

void bindRenderer(py::module_& module);

}  // namespace lic3d::python
