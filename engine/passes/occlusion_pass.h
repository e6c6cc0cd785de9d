// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Directional occlusion for the slice pass (Schott et al. 2009): the slices drawn front to back
// into an image of their own while an occlusion buffer is carried from slice to slice (each slice
// reads the buffer of the one in front, blurred over a cone towards the viewer, and writes it
// with its own opacity added), then that image composited into the frame. One image and two
// ping-pong buffers per eye, made at the viewport's size on demand.
//
// A slice writes the buffer only where it is drawn. A ray meets the box, the clip plane's half
// and the clip box in one interval of slices, so a pixel a slice leaves unwritten is read by no
// later slice; removed fragments (region of interest) still write it.

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <functional>

#include "core/error.h"
#include "gpu/pipelines.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"

namespace lic3d {

class OcclusionPass {
 public:
  static constexpr VkFormat kImageFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
  static constexpr VkFormat kBufferFormat = VK_FORMAT_R16_SFLOAT;
  static constexpr std::array<VkFormat, 2> kFormats{kImageFormat, kBufferFormat};
  static constexpr int kEyes = 2;

  // `context` must outlive the pass.
  static Result<OcclusionPass> create(const Context& context);

  // Draws one slice (`index` counts from the front) inside a rendering of the eye's image and a
  // buffer, with `inFront` the buffer of the slice before it (SHADER_READ_ONLY_OPTIMAL).
  using DrawSlice = std::function<void(VkCommandBuffer, int index, VkImageView inFront)>;

  // Records the front-to-back loop for `eye` (0 or 1) outside any rendering, the images made
  // `extent` large first.
  Result<void> record(VkCommandBuffer cmd, int eye, VkExtent2D extent, int sliceCount,
                      const DrawSlice& drawSlice);

  // Inside the frame's rendering: the eye's finished image over what is there, at `viewport`,
  // writing the channels of `writeMask`.
  Result<void> composite(VkCommandBuffer cmd, int eye, VkFormat format, VkRect2D viewport,
                         VkColorComponentFlags writeMask);

  const Sampler& sampler() const { return sampler_; }

 private:
  struct EyeImages {
    Image image;
    std::array<Image, 2> buffers;
    VkExtent2D extent{0, 0};
  };
  Result<void> resize(EyeImages& eye, VkExtent2D extent) const;

  struct CompositeVariant {
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkColorComponentFlags writeMask = 0;
    bool operator==(const CompositeVariant&) const = default;
  };

  const Context* context_ = nullptr;
  PipelineLayout layout_;
  ShaderModule vertexShader_;
  ShaderModule compositeShader_;
  Sampler sampler_;
  PipelineCache<CompositeVariant> composites_;
  std::array<EyeImages, kEyes> eyes_;
};

}  // namespace lic3d
