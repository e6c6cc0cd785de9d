#pragma once
// The graphics pass: alpha-blended slice proxies through the LIC volume, back to front, into
// whatever colour attachment the caller's dynamic rendering has open. Display variants are
// specialization constants; one pipeline per (variant, attachment format), made on first use.

#include <cstdint>
#include <tuple>
#include <vector>

#include <glm/mat4x4.hpp>
#include <vulkan/vulkan.h>

#include "camera.h"
#include "error.h"
#include "gpu_resources.h"
#include "pipelines.h"
#include "slice_geometry.h"
#include "view_params.h"
#include "vulkan_context.h"

namespace lic3d {

// constant_id i <-> field i (see shaders/slice.frag).
struct SliceSpecialization {
  std::uint32_t opacityMode = 1;
  std::uint32_t orthographic = 0;

  bool operator==(const SliceSpecialization&) const = default;
};

// Everything one draw needs, derived from ViewParams and the volume (see makeSliceFrame).
struct SliceFrame {
  CameraMatrices camera;
  SlicePlan plan;
  glm::vec3 halfExtent{0.5f};
  float alpha = 0.1f;
  float transferScale = 1.0f;   // grey = clamp(scale * intensity + offset)
  float transferOffset = 0.0f;
  SliceSpecialization specialization;
  VolumeFilter filter = VolumeFilter::Linear;
};

// The intensity window and contrast/brightness as one affine map (see ViewParams).
SliceFrame makeSliceFrame(const ViewParams& view, Dims dims, const GridGeometry& geometry,
                          float windowLow, float windowHigh);

class SlicePass {
 public:
  // `context` must outlive the pass.
  static Result<SlicePass> create(const Context& context);

  // Records the draw inside an open dynamic rendering of one `colorFormat` attachment of size
  // `extent`. `volume` must be in SHADER_READ_ONLY_OPTIMAL with its writes visible to fragment
  // shaders.
  Result<void> record(VkCommandBuffer cmd, VkFormat colorFormat, VkExtent2D extent,
                      const Image& volume, const SliceFrame& frame);

  std::size_t variantCount() const { return pipelines_.size(); }

 private:
  Result<VkPipeline> pipelineFor(const SliceSpecialization& specialization, VkFormat format);

  const Context* context_ = nullptr;
  PipelineLayout layout_;
  ShaderModule vertexShader_;
  ShaderModule fragmentShader_;
  Sampler nearest_;
  Sampler linear_;
  std::vector<std::tuple<SliceSpecialization, VkFormat, Pipeline>> pipelines_;
};

}  // namespace lic3d
