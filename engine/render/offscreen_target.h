// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Where offscreen frames go: a colour image of the frame's size in the chosen pixel format, the
// buffer it is copied into, and that copy converted to the 8-bit RGBA pictures are saved as.

#include <vulkan/vulkan.h>

#include <glm/vec3.hpp>

#include "core/error.h"
#include "core/rgba_image.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"

namespace lic3d {

// The offscreen colour buffer. 16 bits per channel keep hundreds of faint slices from banding:
// float (the default) or UNORM, which holds [0, 1] (all blended colours lie there) with 16 bits
// everywhere; 8-bit UNORM halves the blending bandwidth; 10-bit UNORM colour (2-bit alpha, which
// stays 1 over the opaque background) has the 8-bit buffer's pixel size with 4x finer steps.
// Frame times: docs/BENCHMARKS.md.
enum class FramePrecision { Float16, Unorm16, Unorm10, Unorm8 };

class OffscreenTarget {
 public:
  OffscreenTarget() = default;
  // `context` must outlive the target. Fails where the device cannot blend into the format.
  static Result<OffscreenTarget> create(const Context& context, FramePrecision precision);

  // The format of the next frames' image (made anew by the next resize).
  Result<void> setPrecision(FramePrecision precision);
  VkFormat format() const { return format_; }

  // An image of width x height pixels in the current format, unless it already is one.
  Result<void> resize(int width, int height);
  const Image& image() const { return image_; }

  // Records a cleared dynamic rendering of the whole image to `background`; the caller records
  // its draws and vkCmdEndRendering. The previous frame's copy must be recorded before.
  void beginFrame(VkCommandBuffer cmd, glm::vec3 background) const;
  // After the frame's rendering: its copy into the read-back buffer, visible to the host.
  void recordReadback(VkCommandBuffer cmd) const;
  // After the frame's rendering, without a read-back: leaves the image as beginFrame expects it.
  void recordUnread(VkCommandBuffer cmd) const;
  // The frame last copied, once its command buffer has completed, as 8-bit RGBA.
  RgbaImage read() const;

 private:
  const Context* context_ = nullptr;
  VkFormat format_ = VK_FORMAT_R16G16B16A16_SFLOAT;
  Image image_;
  Buffer readback_;
};

}  // namespace lic3d
