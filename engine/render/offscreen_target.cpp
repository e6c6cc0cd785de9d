// SPDX-License-Identifier: BSD-3-Clause
#include "render/offscreen_target.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <glm/gtc/packing.hpp>
#include <string>

#include "core/parallel.h"
#include "gpu/submit.h"

namespace lic3d {
namespace {

VkFormat formatOf(FramePrecision precision) {
  return precision == FramePrecision::Float16   ? VK_FORMAT_R16G16B16A16_SFLOAT
         : precision == FramePrecision::Unorm16 ? VK_FORMAT_R16G16B16A16_UNORM
         : precision == FramePrecision::Unorm10 ? VK_FORMAT_A2B10G10R10_UNORM_PACK32
                                                : VK_FORMAT_R8G8B8A8_UNORM;
}

// Each conversion rounds to the nearest 8-bit value, in integers where the source is.
void fromUnorm10(const void* texels, RgbaImage& image) {
  const auto* packed = static_cast<const std::uint32_t*>(texels);
  parallelChunks(image.pixels.size() / 4, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const std::uint32_t p = packed[i];
      for (int c = 0; c < 3; ++c)  // round(v / 1023 * 255) in integers
        image.pixels[4 * i + c] =
            static_cast<std::uint8_t>((((p >> (10 * c)) & 1023u) * 255u + 511u) / 1023u);
      image.pixels[4 * i + 3] = static_cast<std::uint8_t>((p >> 30) * 85u);
    }
  });
}

void fromUnorm16(const void* texels, RgbaImage& image) {
  const auto* shorts = static_cast<const std::uint16_t*>(texels);
  parallelChunks(image.pixels.size(), [&](std::size_t begin, std::size_t end) {
    // Exactly round(v / 65535 * 255): (v * 255 + 32767) / 65535 in integers.
    for (std::size_t i = begin; i < end; ++i)
      image.pixels[i] = static_cast<std::uint8_t>((shorts[i] * 255u + 32767u) / 65535u);
  });
}

void fromFloat16(const void* texels, RgbaImage& image) {
  const auto* halves = static_cast<const std::uint16_t*>(texels);
  parallelChunks(image.pixels.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const float v = std::clamp(glm::unpackHalf1x16(halves[i]), 0.0f, 1.0f);
      image.pixels[i] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
    }
  });
}

}  // namespace

Result<OffscreenTarget> OffscreenTarget::create(const Context& context, FramePrecision precision) {
  OffscreenTarget target;
  target.context_ = &context;
  LIC3D_TRY(target.setPrecision(precision));
  return target;
}

Result<void> OffscreenTarget::setPrecision(FramePrecision precision) {
  const VkFormat format = formatOf(precision);
  if (!supportsFormat(*context_, format, VK_FORMAT_FEATURE_2_COLOR_ATTACHMENT_BLEND_BIT))
    return unsupportedError(context_->deviceInfo().name + " cannot blend into the frame format");
  format_ = format;
  return {};
}

Result<void> OffscreenTarget::resize(int width, int height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    return inputError("image size must be 1..16384 pixels per side, got " + std::to_string(width) +
                      "x" + std::to_string(height));
  const std::uint32_t limit = context_->properties().limits.maxImageDimension2D;
  if (static_cast<std::uint32_t>(std::max(width, height)) > limit)
    return inputError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                      " exceeds the device's limit of " + std::to_string(limit));
  if (image_ && image_.format() == format_ &&
      image_.extent().width == static_cast<std::uint32_t>(width) &&
      image_.extent().height == static_cast<std::uint32_t>(height))
    return {};
  image_ = Image();
  readback_ = Buffer();
  ImageDesc desc;
  desc.type = VK_IMAGE_TYPE_2D;
  desc.format = format_;
  desc.extent = {static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height), 1};
  desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  desc.name = "offscreen colour";
  LIC3D_TRY_ASSIGN(image_, Image::create(*context_, desc));
  LIC3D_TRY_ASSIGN(
      readback_,
      Buffer::create(*context_, static_cast<VkDeviceSize>(width) * height * 8,
                     VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback, "offscreen readback"));
  return {};
}

void OffscreenTarget::beginFrame(VkCommandBuffer cmd, glm::vec3 background) const {
  // The previous frame's copy must finish reading before the image is cleared again.
  imageBarrier(cmd, image_.handle(), VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
               VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT);
  const VkExtent2D extent{image_.extent().width, image_.extent().height};
  beginClearedRendering(cmd, image_.view(), extent, background);
}

void OffscreenTarget::recordReadback(VkCommandBuffer cmd) const {
  imageBarrier(cmd, image_.handle(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
               VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
               VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
               VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = image_.extent();
  vkCmdCopyImageToBuffer(cmd, image_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         readback_.handle(), 1, &region);
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
}

void OffscreenTarget::recordUnread(VkCommandBuffer cmd) const {
  imageBarrier(
      cmd, image_.handle(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
      VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE);
}

RgbaImage OffscreenTarget::read() const {
  RgbaImage image;
  image.width = static_cast<int>(image_.extent().width);
  image.height = static_cast<int>(image_.extent().height);
  image.pixels.resize(static_cast<std::size_t>(image.width) * image.height * 4);
  const VkFormat format = image_.format();
  if (format == VK_FORMAT_R8G8B8A8_UNORM) {
    std::memcpy(image.pixels.data(), readback_.mapped(), image.pixels.size());
  } else if (format == VK_FORMAT_A2B10G10R10_UNORM_PACK32) {
    fromUnorm10(readback_.mapped(), image);
  } else if (format == VK_FORMAT_R16G16B16A16_UNORM) {
    fromUnorm16(readback_.mapped(), image);
  } else {
    fromFloat16(readback_.mapped(), image);
  }
  return image;
}

}  // namespace lic3d
