// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The 2D LIC compute pass (thesis chapter 3): one invocation per output pixel writes the LIC
// image. Its inputs are two 2D textures, the field at its own grid and the noise at the output
// image's resolution (which may be finer). Each (integrator, kernel, noise filter, direction)
// variant is its own pipeline, specialized at creation and cached, as in LicPass.

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <glm/vec2.hpp>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/lic_params.h"
#include "core/volume.h"
#include "gpu/pipelines.h"
#include "gpu/resources.h"
#include "gpu/timer.h"
#include "gpu/vulkan_context.h"
#include "passes/volume_textures.h"
#include "shared_layout.h"

namespace lic3d {

// constant_id i <-> field i (see shaders/lic2d.comp), each defaulting to the shader's default
// (shared_layout.h).
struct Lic2DSpecialization {
  std::uint32_t integrator = gpu::kLic2DDefaultIntegrator;
  std::uint32_t kernel = gpu::kLic2DDefaultKernel;
  std::uint32_t noiseFilter = gpu::kLic2DDefaultNoiseFilter;
  std::uint32_t direction = gpu::kLic2DDefaultDirection;
  std::uint32_t localSizeX = gpu::kLic2DDefaultLocalSizeX;
  std::uint32_t localSizeY = gpu::kLic2DDefaultLocalSizeY;
  std::uint32_t scheme = gpu::kLic2DDefaultScheme;

  bool operator==(const Lic2DSpecialization&) const = default;
};
static_assert(sizeof(Lic2DSpecialization) == 7 * 4);
static_assert(offsetof(Lic2DSpecialization, integrator) == 4 * gpu::kLic2DConstIntegrator);
static_assert(offsetof(Lic2DSpecialization, kernel) == 4 * gpu::kLic2DConstKernel);
static_assert(offsetof(Lic2DSpecialization, noiseFilter) == 4 * gpu::kLic2DConstNoiseFilter);
static_assert(offsetof(Lic2DSpecialization, direction) == 4 * gpu::kLic2DConstDirection);
static_assert(offsetof(Lic2DSpecialization, localSizeX) == 4 * gpu::kLic2DConstLocalSizeX);
static_assert(offsetof(Lic2DSpecialization, localSizeY) == 4 * gpu::kLic2DConstLocalSizeY);
static_assert(offsetof(Lic2DSpecialization, scheme) == 4 * gpu::kLic2DConstScheme);

Lic2DSpecialization lic2DSpecialization(const LicParams& params);

// The inputs of one 2D LIC image. The field texture holds xy = u / max|u|, u the field in output
// pixel units (FieldSampler(field, image size) in lic_reference.h), as RG16F on GPUs or RG32F
// (FieldPrecision); the noise texture holds the noise values as read (R8 for byte noise, else
// R32F) at the image's size.
struct Lic2DInputs {
  Image field;
  Image noise;
  Dims fieldDims{0};      // NX x NY x 1
  Dims imageDims{0};      // W x H x 1: the noise's and the output's size
  double maxSpeed = 0.0;  // the texels' scale
  FieldPrecision precision = FieldPrecision::Half;
};

// Fails with InvalidInput for inputs 2D LIC cannot take (checkLic2DInputs) or sizes beyond the
// device's 2D image limit.
Result<Lic2DInputs> uploadLic2DInputs(const Context& context, const VectorField& field,
                                      const NoiseVolume& noise, FieldPrecision precision);

// The format of 2D LIC images: one float per pixel.
inline constexpr VkFormat kLic2DImageFormat = VK_FORMAT_R32_SFLOAT;

class Lic2DPass {
 public:
  // `context` must outlive the pass.
  static Result<Lic2DPass> create(const Context& context);

  // Records the dispatch over the whole image. The inputs must be in SHADER_READ_ONLY_OPTIMAL
  // and `output` (kLic2DImageFormat, the inputs' image size) in GENERAL; barriers are the
  // caller's.
  Result<void> record(VkCommandBuffer cmd, const Lic2DInputs& inputs, const Image& output,
                      const LicParams& params);

  // The blocking recipe: makes an output image, records, submits, waits and reads the LIC image
  // back (geometry left to the caller).
  Result<ScalarVolume> compute(const Lic2DInputs& inputs, const LicParams& params);
  // GPU milliseconds of the last compute()'s dispatch (timestamp queries; 0 where the queue has
  // none).
  double lastMilliseconds() const { return lastMs_; }

  std::size_t variantCount() const { return pipelines_.size(); }

 private:
  const Context* context_ = nullptr;
  PipelineLayout layout_;
  ShaderModule shader_;
  Sampler linear_;
  GpuTimer timer_;
  double lastMs_ = 0.0;
  PipelineCache<Lic2DSpecialization> pipelines_;
};

}  // namespace lic3d
