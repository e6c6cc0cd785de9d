#include "commands.h"

#include <cstdio>
#include <limits>

#include "lic_reference.h"
#include "lic_renderer.h"
#include "nrrd.h"
#include "progress.h"
#include "vulkan_context.h"

namespace lic3d::cli {
namespace {

Result<Context> openContext(const GlobalOptions& global) {
  ContextOptions options;
  options.validation = global.validation;
  options.device = global.device;
  return Context::create(options);
}

// With validation on, any message fails the command even if it otherwise succeeded.
int finish(const Context& context, int status) {
  if (context.validationEnabled() && context.validationMessageCount() > 0) {
    std::fprintf(stderr, "lic3d: error: %zu validation message(s)\n",
                 context.validationMessageCount());
    return status == kExitOk ? kExitFailure : status;
  }
  return status;
}

std::string gridText(Dims d) {
  return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

struct Inputs {
  VectorField field;
  NoiseVolume noise;
};

Result<Inputs> loadInputs(const ComputeOptions& options) {
  const Session& session = options.inputs.session;
  LIC3D_TRY(validate(session.lic));
  Inputs inputs;
  LIC3D_TRY_ASSIGN(inputs.field, loadField(session.field, options.inputs.grid.given()));
  LIC3D_TRY(validate(session.lic.sparsity, inputs.field.dims));
  LIC3D_TRY_ASSIGN(inputs.noise, loadNoise(session.noise, inputs.field.dims));
  return inputs;
}

Result<ScalarVolume> computeOnCpu(const GlobalOptions& global, const Inputs& inputs,
                                  const LicParams& lic) {
  Progress progress("LIC " + gridText(inputs.field.dims) + " on the CPU", global.quiet);
  return computeLicReference(inputs.field, inputs.noise, lic, 0,
                             [&](double f) { progress.update(f); });
}

// Uploads the inputs and makes the LIC volume, on the GPU or (with --cpu) the CPU.
Result<void> prepareRenderer(const GlobalOptions& global, const ComputeOptions& options,
                             const Inputs& inputs, LicRenderer& renderer) {
  LIC3D_TRY(renderer.setInputs(inputs.field, inputs.noise));
  const LicParams& lic = options.inputs.session.lic;
  if (options.cpu) {
    LIC3D_TRY_ASSIGN(const ScalarVolume volume, computeOnCpu(global, inputs, lic));
    return renderer.setLicVolume(volume, lic);
  }
  Progress progress("LIC " + gridText(inputs.field.dims) + " on the GPU", global.quiet);
  LIC3D_TRY_ASSIGN([[maybe_unused]] const bool ran,
                   renderer.updateLic(lic, [&](double f) { progress.update(f); }));
  return {};
}

// Voxels that sparsity hides are written as NaN: "no value" to ParaView and VisIt.
Result<void> writeLicVolume(const std::string& path, const ScalarVolume& volume) {
  if (volume.drawn.empty()) return writeScalarNrrd(path, volume);
  ScalarVolume marked = volume;
  for (std::size_t i = 0; i < marked.values.size(); ++i)
    if (!marked.drawn[i]) marked.values[i] = std::numeric_limits<float>::quiet_NaN();
  return writeScalarNrrd(path, marked);
}

}  // namespace

int runDevices(const GlobalOptions& global) {
  (void)global;
  const Result<std::vector<DeviceInfo>> devices = listDevices();
  if (!devices) return reportError(devices.error());
  if (devices->empty()) {
    std::fprintf(stderr, "lic3d: no Vulkan device found\n");
    return kExitFailure;
  }
  for (const DeviceInfo& d : *devices) {
    std::printf("%d: %s (%s, Vulkan %u.%u, %s, %.1f GiB device-local)%s%s\n", d.index,
                d.name.c_str(), deviceTypeName(d.type), VK_API_VERSION_MAJOR(d.apiVersion),
                VK_API_VERSION_MINOR(d.apiVersion), d.driver.c_str(),
                static_cast<double>(d.deviceLocalBytes) / (1024.0 * 1024.0 * 1024.0),
                d.usable ? "" : " - unusable: ", d.usable ? "" : d.unusableReason.c_str());
  }
  return kExitOk;
}

int runCompute(const GlobalOptions& global, const ComputeOptions& options) {
  if (auto r = checkOutputPath(options.output, ".nrrd"); !r) return reportError(r.error());
  Result<Inputs> inputs = loadInputs(options);
  if (!inputs) return reportError(inputs.error());

  if (options.cpu) {
    const Result<ScalarVolume> volume = computeOnCpu(global, *inputs, options.inputs.session.lic);
    if (!volume) return reportError(volume.error());
    if (auto r = writeLicVolume(options.output, *volume); !r) return reportError(r.error());
    if (!global.quiet) std::fprintf(stderr, "lic3d: wrote %s\n", options.output.c_str());
    return kExitOk;
  }

  Result<Context> context = openContext(global);
  if (!context) return reportError(context.error());
  int status = kExitOk;
  {
    Result<LicRenderer> renderer =
        LicRenderer::create(*context, {options.inputs.session.precision});
    Result<void> done = renderer ? prepareRenderer(global, options, *inputs, *renderer)
                                 : Result<void>(renderer.error());
    Result<ScalarVolume> volume = done ? renderer->readLicVolume() : Result<ScalarVolume>(done.error());
    if (volume) done = writeLicVolume(options.output, *volume);
    else done = volume.error();
    if (!done) status = reportError(done.error());
    else if (!global.quiet)
      std::fprintf(stderr, "lic3d: wrote %s (%s on %s)\n", options.output.c_str(),
                   gridText(inputs->field.dims).c_str(), context->deviceInfo().name.c_str());
  }
  return finish(*context, status);
}

int runRender(const GlobalOptions& global, const ComputeOptions& options) {
  const ComputeOptions& compute = options;
  const Session& session = options.inputs.session;
  if (auto r = checkOutputPath(compute.output, ".png"); !r) return reportError(r.error());
  Result<Inputs> inputs = loadInputs(compute);
  if (!inputs) return reportError(inputs.error());
  Result<Context> context = openContext(global);
  if (!context) return reportError(context.error());

  int status = kExitOk;
  {
    Result<LicRenderer> renderer = LicRenderer::create(*context, {session.precision});
    Result<void> done = renderer ? prepareRenderer(global, compute, *inputs, *renderer)
                                 : Result<void>(renderer.error());
    Result<RgbaImage> image =
        done ? renderer->render(session.lic, session.view) : Result<RgbaImage>(done.error());
    if (image) done = writePng(compute.output, *image);
    else done = image.error();
    if (!done) status = reportError(done.error());
    else if (!global.quiet)
      std::fprintf(stderr, "lic3d: wrote %s (%dx%d, %s %s, on %s)\n", compute.output.c_str(),
                   image->width, image->height, session.field.field.c_str(),
                   gridText(inputs->field.dims).c_str(), context->deviceInfo().name.c_str());
  }
  return finish(*context, status);
}

}  // namespace lic3d::cli
