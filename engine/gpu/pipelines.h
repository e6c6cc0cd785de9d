// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Shader modules, pipeline layouts (with their push-descriptor set layout), pipelines and their
// variant cache, and the descriptors a pass pushes: the few calls every pass makes to build and
// bind its pipelines.

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "gpu/resources.h"
#include "gpu/shader_library.h"
#include "gpu/vulkan_context.h"

namespace lic3d {

using ShaderModule = DeviceHandle<VkShaderModule, vkDestroyShaderModule>;
using Pipeline = DeviceHandle<VkPipeline, vkDestroyPipeline>;

Result<ShaderModule> loadShader(const Context& context, ShaderId id);

// One descriptor of a pass's push-descriptor set (shaders/shared_layout.h numbers them).
struct Binding {
  std::uint32_t binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  VkShaderStageFlags stages = VK_SHADER_STAGE_COMPUTE_BIT;
};

// One push-descriptor set (the pass's bindings) and one push-constant range (none if 0 bytes).
class PipelineLayout {
 public:
  PipelineLayout() = default;
  static Result<PipelineLayout> create(const Context& context, std::span<const Binding> bindings,
                                       VkShaderStageFlags pushStages, std::uint32_t pushBytes,
                                       const std::string& name);

  VkPipelineLayout get() const { return layout_.get(); }

 private:
  DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout> setLayout_;
  DeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout> layout_;
};

Result<Pipeline> createComputePipeline(const Context& context, const ShaderModule& shader,
                                       const PipelineLayout& layout,
                                       const VkSpecializationInfo* specialization,
                                       const std::string& name);

// A graphics pipeline for dynamic rendering: triangle lists without vertex buffers, no culling,
// no depth, one sample, viewport and scissor dynamic; one blend state per colour attachment.
struct GraphicsPipelineDesc {
  VkShaderModule vertex = VK_NULL_HANDLE;
  VkShaderModule fragment = VK_NULL_HANDLE;
  const VkSpecializationInfo* specialization = nullptr;  // both stages'
  std::span<const VkFormat> colorFormats;
  std::span<const VkPipelineColorBlendAttachmentState> blends;  // one per format
  const PipelineLayout* layout = nullptr;
  std::string name;
};
Result<Pipeline> createGraphicsPipeline(const Context& context, const GraphicsPipelineDesc& desc);

// Premultiplied-alpha blending: "over" for layers drawn back to front (dst = src + (1 - src.a)
// dst), "under" for layers drawn front to back (dst = dst + (1 - dst.a) src).
VkPipelineColorBlendAttachmentState blendOver(VkColorComponentFlags writeMask);
VkPipelineColorBlendAttachmentState blendUnder();
inline constexpr VkColorComponentFlags kWriteRgba =
    VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
    VK_COLOR_COMPONENT_A_BIT;

// The pipeline variants of a pass, each made the first time its key (a specialization struct,
// or one with the attachment format) is asked for and kept for the pass's life.
template <class Key>
class PipelineCache {
 public:
  // `make(key)` returns Result<Pipeline> for a key not seen before.
  template <class Make>
  Result<VkPipeline> get(const Key& key, const Make& make) {
    for (const auto& [known, pipeline] : pipelines_)
      if (known == key) return pipeline.get();
    LIC3D_TRY_ASSIGN(Pipeline pipeline, make(key));
    const VkPipeline handle = pipeline.get();
    pipelines_.emplace_back(key, std::move(pipeline));
    return handle;
  }
  std::size_t size() const { return pipelines_.size(); }
  // The pipeline made for `key`, or VK_NULL_HANDLE.
  VkPipeline find(const Key& key) const {
    for (const auto& [known, pipeline] : pipelines_)
      if (known == key) return pipeline.get();
    return VK_NULL_HANDLE;
  }

 private:
  std::vector<std::pair<Key, Pipeline>> pipelines_;
};

// The driver's statistics of a pipeline's compiled shaders (name and value as text, e.g.
// registers per invocation), when the context captures them (capturesPipelineStatistics); empty
// otherwise.
std::vector<std::pair<std::string, std::string>> pipelineStatistics(const Context& context,
                                                                    VkPipeline pipeline);

// The descriptors of one dispatch or draw, pushed with vkCmdPushDescriptorSetKHR: sampled images
// in SHADER_READ_ONLY_OPTIMAL, storage images in GENERAL, whole storage buffers, uniform ranges.
class DescriptorWrites {
 public:
  DescriptorWrites& sampledImage(std::uint32_t binding, const Sampler& sampler, VkImageView view);
  DescriptorWrites& storageImage(std::uint32_t binding, VkImageView view);
  DescriptorWrites& storageBuffer(std::uint32_t binding, const Buffer& buffer);
  DescriptorWrites& uniformBuffer(std::uint32_t binding, const Buffer& buffer, VkDeviceSize offset,
                                  VkDeviceSize range);
  void push(const Context& context, VkCommandBuffer cmd, VkPipelineBindPoint bindPoint,
            const PipelineLayout& layout);

 private:
  static constexpr std::size_t kMax = 8;
  VkWriteDescriptorSet& add(std::uint32_t binding, VkDescriptorType type);
  std::array<VkWriteDescriptorSet, kMax> writes_{};
  std::array<VkDescriptorImageInfo, kMax> images_{};
  std::array<VkDescriptorBufferInfo, kMax> buffers_{};
  std::uint32_t count_ = 0;
};

}  // namespace lic3d
