// SPDX-License-Identifier: BSD-3-Clause
#include "passes/visible_bricks_pass.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "core/colormap.h"
#include "gpu/shader_library.h"
#include "gpu/submit.h"
#include "gpu/vk_check.h"

namespace lic3d {

namespace {

constexpr int kBrick = static_cast<int>(gpu::kVisibleBrickSize);

// The dispatch commands of the brick layers: vkCmdUpdateBuffer writes them whole.
constexpr std::uint32_t kMaxLayers = 65536 / (3 * sizeof(std::uint32_t));

}  // namespace

glm::ivec3 brickCounts(Dims dims) { return (glm::ivec3(dims) + kBrick - 1) / kBrick; }

VisibleBricksSetup visibleBricksSetup(const gpu::SliceUniforms& u, const SliceSpecialization& s,
                                      Dims dims, float tableOpaqueFrom, float jitterMargin) {
  VisibleBricksSetup setup;
  VisibleBricksSpecialization& v = setup.specialization;
  const bool shadesBySpeed = s.colorMode == 1 || s.magnitudeOpacity == 1 || s.opacityTable == 1;
  // slice.frag: alpha = 0 where the colour or the opacity value is NaN, which is the speed where
  // either follows it; the threshold where opacity follows the speed.
  const bool nanTest = shadesBySpeed && (s.colorSource == 0 || s.opacitySource == 0);
  const bool threshold = (s.magnitudeOpacity == 1 || s.opacityTable == 1) && s.opacitySource == 0;
  v.opacityRule = threshold ? 2u : nanTest ? 1u : 0u;
  v.packing = s.fieldPacking;
  v.clipPlane = s.clipPlane;
  v.roiShape = s.roiShape;
  v.roiOutside = s.roiOutside;

  gpu::VisibleBricksUniforms& b = setup.uniforms;
  // Linear and nearest filtering read the 8 voxels of the fragment's cell, the cubic B-spline 4
  // per axis; tube lighting's gradient reads one voxel further.
  int margin = (s.filter == 2 ? 2 : 1) + (s.lighting == 3 ? 1 : 0);
  // Where the opacity follows the LIC, a halo's ring taps read the LIC volume (linearly) up to
  // the ring's radius R from a sample, with the sample's weight: a tap's cell lies at most
  // floor(R) + 1 voxels from the sample's, so the margin becomes floor(R) + 2.
  if (s.halo == 1 && (s.opacityMode == 1 || s.sparsity == 1)) {
    const glm::vec3 voxelsPerUnit = glm::vec3(dims) / (2.0f * glm::vec3(u.halfExtent));
    const float ring =
        u.screenRight.w * std::max({voxelsPerUnit.x, voxelsPerUnit.y, voxelsPerUnit.z});
    margin = std::max(margin, 2 + static_cast<int>(std::floor(ring)));
  }
  b.roiFromTexture = u.roiFromTexture;
  b.dims = glm::ivec4(dims, margin);
  b.bricks = glm::ivec4(brickCounts(dims), 0);
  b.halfExtent = glm::vec4(glm::vec3(u.halfExtent), jitterMargin);
  b.clipMin = u.clipMin;
  b.clipMax = u.clipMax;
  b.clipPlane = u.clipPlane;
  b.texelToPhysical = u.texelToPhysical;
  const float from = s.opacityTable == 1 ? tableOpaqueFrom : u.magnitudeOpacity.y;
  b.opacity =
      glm::vec4(u.magnitudeOpacity.z, u.magnitudeOpacity.w, from - kOpacityThresholdMargin, 0.0f);
  return setup;
}

bool sameClassification(const VisibleBricksSetup& a, const VisibleBricksSetup& b) {
  return a.specialization == b.specialization &&
         std::memcmp(&a.uniforms, &b.uniforms, sizeof(a.uniforms)) == 0;
}

float sampleReach(const SliceFrame& frame) {
  const SliceSpecialization& s = frame.specialization;
  const gpu::SliceUniforms& u = frame.uniforms;
  float reach = 0.0f;
  if (s.jitter == 1) {
    // slice.frag moves a sample by up to half the plane spacing over |cos| of the angle between
    // its ray and the plane normal; the rays of a perspective view lie in the cone of the
    // frustum's corner rays, whose smallest |cos| is at a corner (or 0 when the cone holds a
    // direction in the plane).
    const glm::vec3 normal(u.planeNormal);
    float lowest = std::abs(glm::dot(glm::vec3(u.toViewer), normal));
    if (s.orthographic == 0) {
      const glm::mat4 inverse = glm::inverse(frame.camera.viewProjection);
      float cosines[4];
      for (int k = 0; k < 4; ++k) {
        const glm::vec4 p =
            inverse * glm::vec4((k & 1) ? 1.0f : -1.0f, (k & 2) ? 1.0f : -1.0f, 0.5f, 1.0f);
        const glm::vec3 ray = glm::normalize(glm::vec3(p) / p.w - frame.camera.eye);
        cosines[k] = glm::dot(ray, normal);
        lowest = std::min(lowest, std::abs(cosines[k]));
      }
      for (int k = 1; k < 4; ++k)
        if ((cosines[k] < 0.0f) != (cosines[0] < 0.0f)) lowest = 0.0f;
    }
    reach += 0.5f * u.eyePosition.w / std::max(lowest, 1e-3f);
  }
  // A halo's ring samples lie the ring's radius from the (jittered) sample.
  if (s.halo == 1) reach += u.screenRight.w;
  return reach;
}

VisibleBricksSetup visibleBricksSetup(const SliceFrame& frame, Dims dims,
                                      std::span<const std::uint8_t> table) {
  float tableOpaqueFrom = 0.0f;
  if (frame.specialization.opacityTable == 1) {
    std::vector<float> alphas(kColormapWidth);
    for (int i = 0; i < kColormapWidth; ++i)
      alphas[i] = static_cast<float>(table[4 * (kCustomColormapRow * kColormapWidth + i) + 3]);
    tableOpaqueFrom = opaqueFromTable(alphas);
  }
  VisibleBricksSetup setup = visibleBricksSetup(frame.uniforms, frame.specialization, dims,
                                                tableOpaqueFrom, sampleReach(frame));
  // The ring samples of a halo are read around a kept sample without the region test.
  if (frame.specialization.halo == 1) setup.uniforms.opacity.w = frame.uniforms.screenRight.w;
  return setup;
}

VisibleBricksSetup unionOf(const VisibleBricksSetup& a, const VisibleBricksSetup& b) {
  VisibleBricksSetup both = a;
  both.uniforms.dims.w = std::max(a.uniforms.dims.w, b.uniforms.dims.w);
  both.uniforms.halfExtent.w = std::max(a.uniforms.halfExtent.w, b.uniforms.halfExtent.w);
  both.uniforms.opacity.w = std::max(a.uniforms.opacity.w, b.uniforms.opacity.w);
  return both;
}

float opaqueFromTable(std::span<const float> alphas) {
  const std::size_t n = alphas.size();
  for (std::size_t i = 0; i < n; ++i)
    if (alphas[i] > 0.0f)
      return i == 0 || n < 2 ? 0.0f : static_cast<float>(i - 1) / static_cast<float>(n - 1);
  return 2.0f;
}

namespace {

// visible_bricks.comp's tests, in the same float arithmetic.
struct CpuRule {
  const gpu::VisibleBricksUniforms& u;
  const VisibleBricksSpecialization& s;

  glm::vec3 textureAt(glm::vec3 voxel) const {
    return (voxel + 0.5f) / glm::vec3(glm::ivec3(u.dims));
  }
  glm::vec3 worldAt(glm::vec3 voxel) const {
    return (textureAt(voxel) - 0.5f) * 2.0f * glm::vec3(u.halfExtent);
  }
  bool insideRegion(glm::vec3 p) const {
    if (s.roiShape == 1) return glm::dot(p, p) <= 0.25f;
    if (s.roiShape == 2)
      return std::abs(p.x) <= 0.5f && std::abs(p.y) <= 0.5f && std::abs(p.z) <= 0.5f;
    return p.x * p.x + p.y * p.y <= 0.25f && std::abs(p.z) <= 0.5f;
  }
  bool keptBox(glm::vec3 lo, glm::vec3 hi) const {
    const float jitter = u.halfExtent.w;
    const glm::vec3 worldLo = worldAt(lo) - jitter;
    const glm::vec3 worldHi = worldAt(hi) + jitter;
    for (int a = 0; a < 3; ++a)
      if (worldLo[a] > u.clipMax[a] || worldHi[a] < u.clipMin[a]) return false;
    if (s.clipPlane == 1) {
      const glm::vec3 n(u.clipPlane);
      glm::vec3 lowest;
      for (int a = 0; a < 3; ++a) lowest[a] = n[a] >= 0.0f ? worldLo[a] : worldHi[a];
      if (glm::dot(n, lowest) > u.clipPlane.w) return false;
    }
    if (s.roiShape != 0) {
      const glm::vec3 ring = u.opacity.w / (2.0f * glm::vec3(u.halfExtent));
      const glm::vec3 tLo = textureAt(lo) - ring, tHi = textureAt(hi) + ring;
      std::array<glm::vec3, 8> corners;
      for (int k = 0; k < 8; ++k) {
        const glm::vec3 t((k & 1) ? tHi.x : tLo.x, (k & 2) ? tHi.y : tLo.y,
                          (k & 4) ? tHi.z : tLo.z);
        corners[k] = glm::vec3(u.roiFromTexture * glm::vec4(t, 1.0f));
      }
      if (s.roiOutside == 1)
        return !std::all_of(corners.begin(), corners.end(),
                            [&](glm::vec3 c) { return insideRegion(c); });
      glm::vec3 boundsLo = corners[0], boundsHi = corners[0];
      for (const glm::vec3& c : corners) {
        boundsLo = glm::min(boundsLo, c);
        boundsHi = glm::max(boundsHi, c);
      }
      if (s.roiShape != 1)
        for (int a = 0; a < 3; ++a)
          if (boundsLo[a] > 0.5f || boundsHi[a] < -0.5f) return false;
      if (s.roiShape != 2) {
        const glm::vec3 centre = 0.5f * (corners[0] + corners[7]);
        float radius = 0.0f;
        for (const glm::vec3& c : corners) radius = std::max(radius, glm::distance(c, centre));
        const float reach =
            s.roiShape == 1 ? glm::length(centre) : glm::length(glm::vec2(centre.x, centre.y));
        if (reach > 0.5f + radius) return false;
      }
    }
    return true;
  }
  bool opaqueCapable(float speed) const {
    if (std::isnan(speed)) return false;
    if (s.opacityRule == 1) return true;
    const float o = std::clamp((speed - u.opacity.x) * u.opacity.y, 0.0f, 1.0f);
    return o >= u.opacity.z;
  }
};

}  // namespace

std::vector<std::uint32_t> classifyBricksOnCpu(const VisibleBricksSetup& setup, Dims dims,
                                               std::span<const float> speeds) {
  const CpuRule rule{setup.uniforms, setup.specialization};
  const glm::ivec3 bricks = brickCounts(dims);
  const glm::ivec3 grid(dims);
  const int margin = setup.uniforms.dims.w;
  std::vector<std::uint32_t> flags(static_cast<std::size_t>(bricks.x) * bricks.y * bricks.z);
  for (int bz = 0; bz < bricks.z; ++bz)
    for (int by = 0; by < bricks.y; ++by)
      for (int bx = 0; bx < bricks.x; ++bx) {
        const glm::ivec3 first = glm::ivec3(bx, by, bz) * kBrick;
        const glm::ivec3 last = glm::min(first + kBrick, grid) - 1;
        bool shown = rule.keptBox(glm::vec3(first - margin), glm::vec3(last + margin));
        if (shown && setup.specialization.opacityRule != 0) {
          const glm::ivec3 lo = glm::max(first - margin, glm::ivec3(0));
          const glm::ivec3 hi = glm::min(last + margin, grid - 1);
          bool found = false;
          for (int z = lo.z; z <= hi.z && !found; ++z)
            for (int y = lo.y; y <= hi.y && !found; ++y)
              for (int x = lo.x; x <= hi.x && !found; ++x)
                found = rule.opaqueCapable(
                    speeds[(static_cast<std::size_t>(z) * grid.y + y) * grid.x + x]);
          shown = found;
        }
        flags[(static_cast<std::size_t>(bz) * bricks.y + by) * bricks.x + bx] = shown ? 1u : 0u;
      }
  return flags;
}

Result<VisibleBricksPass> VisibleBricksPass::create(const Context& context) {
  VisibleBricksPass pass;
  pass.context_ = &context;
  constexpr Binding bindings[] = {
      {gpu::kVisibleBindingField},
      {gpu::kVisibleBindingUniforms, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
      {gpu::kVisibleBindingVisible, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
      {gpu::kVisibleBindingMade, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
      {gpu::kVisibleBindingLists, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
      {gpu::kVisibleBindingDispatch, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
  };
  LIC3D_TRY_ASSIGN(
      pass.layout_,
      PipelineLayout::create(context, bindings, VK_SHADER_STAGE_COMPUTE_BIT, 0, "visible bricks"));
  LIC3D_TRY_ASSIGN(pass.shader_, loadShader(context, ShaderId::VisibleBricks));
  LIC3D_TRY_ASSIGN(pass.sampler_,
                   Sampler::create(context, VK_FILTER_NEAREST, "visible bricks sampler"));
  LIC3D_TRY_ASSIGN(
      pass.uniforms_,
      Buffer::create(context, sizeof(gpu::VisibleBricksUniforms),
                     VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                     MemoryUse::DeviceLocal, "visible bricks uniforms"));
  return pass;
}

Result<void> VisibleBricksPass::reserve(Dims dims) {
  const glm::ivec3 bricks = brickCounts(dims);
  if (bricks == bricks_) return {};
  if (static_cast<std::uint32_t>(bricks.z) > kMaxLayers)
    return unsupportedError("visible bricks: at most " + std::to_string(kMaxLayers) +
                            " brick layers along z, found " + std::to_string(bricks.z));
  const VkDeviceSize count = static_cast<VkDeviceSize>(bricks.x) * bricks.y * bricks.z;
  const VkDeviceSize bytes = count * sizeof(std::uint32_t);
  const VkDeviceSize dispatchBytes =
      3 * sizeof(std::uint32_t) * static_cast<VkDeviceSize>(bricks.z);
  constexpr VkBufferUsageFlags kUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  LIC3D_TRY_ASSIGN(
      visible_, Buffer::create(*context_, bytes, kUsage, MemoryUse::DeviceLocal, "visible bricks"));
  LIC3D_TRY_ASSIGN(made_,
                   Buffer::create(*context_, bytes, kUsage, MemoryUse::DeviceLocal, "made bricks"));
  LIC3D_TRY_ASSIGN(lists_,
                   Buffer::create(*context_, bytes, kUsage, MemoryUse::DeviceLocal, "brick lists"));
  LIC3D_TRY_ASSIGN(dispatch_, Buffer::create(*context_, dispatchBytes,
                                             kUsage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                                             MemoryUse::DeviceLocal, "brick dispatch"));
  LIC3D_TRY_ASSIGN(readback_, Buffer::create(*context_, 2 * bytes + dispatchBytes,
                                             VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback,
                                             "visible bricks readback"));
  bricks_ = bricks;
  return submitAndWait(
      *context_, [&](VkCommandBuffer cmd) { recordForget(cmd); }, "visible bricks reset");
}

void VisibleBricksPass::recordForget(VkCommandBuffer cmd) { recordFillMade(cmd, 0); }

void VisibleBricksPass::recordAllMade(VkCommandBuffer cmd) { recordFillMade(cmd, 1); }

void VisibleBricksPass::recordFillMade(VkCommandBuffer cmd, std::uint32_t value) {
  // The last classification reads the flags; the LIC pass' brick variant writes them.
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  vkCmdFillBuffer(cmd, made_.handle(), 0, VK_WHOLE_SIZE, value);
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

Result<void> VisibleBricksPass::record(VkCommandBuffer cmd, const FieldTexture& field,
                                       const VisibleBricksSetup& setup) {
  LIC3D_ASSERT(brickCounts(field.dims) == bricks_);
  const VisibleBricksSpecialization key = setup.specialization;
  LIC3D_TRY_ASSIGN(
      const VkPipeline pipeline, pipelines_.get(key, [&](const VisibleBricksSpecialization& k) {
        const Specialization<VisibleBricksSpecialization> spec(k);
        return createComputePipeline(*context_, shader_, layout_, spec.info(), "visible bricks");
      }));

  // The previous classification, the LIC dispatches it fed and the read-back are done with the
  // buffers before they are written again.
  memoryBarrier(cmd,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT |
                    VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                    VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_UNIFORM_READ_BIT |
                    VK_ACCESS_2_TRANSFER_READ_BIT,
                VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  vkCmdUpdateBuffer(cmd, uniforms_.handle(), 0, sizeof(setup.uniforms), &setup.uniforms);
  std::vector<std::uint32_t> commands(3 * static_cast<std::size_t>(bricks_.z));
  for (std::size_t layer = 0; layer < static_cast<std::size_t>(bricks_.z); ++layer) {
    commands[3 * layer] = 0;
    commands[3 * layer + 1] = gpu::kVisibleBrickSize;
    commands[3 * layer + 2] = 1;
  }
  vkCmdUpdateBuffer(cmd, dispatch_.handle(), 0, commands.size() * sizeof(std::uint32_t),
                    commands.data());
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_UNIFORM_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                    VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);

  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
  DescriptorWrites()
      .sampledImage(gpu::kVisibleBindingField, sampler_, field.image.view())
      .uniformBuffer(gpu::kVisibleBindingUniforms, uniforms_, 0, sizeof(gpu::VisibleBricksUniforms))
      .storageBuffer(gpu::kVisibleBindingVisible, visible_)
      .storageBuffer(gpu::kVisibleBindingMade, made_)
      .storageBuffer(gpu::kVisibleBindingLists, lists_)
      .storageBuffer(gpu::kVisibleBindingDispatch, dispatch_)
      .push(*context_, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_);
  vkCmdDispatch(cmd, static_cast<std::uint32_t>(bricks_.x), static_cast<std::uint32_t>(bricks_.y),
                static_cast<std::uint32_t>(bricks_.z));

  // For the LIC pass' indirect dispatches, its reads of the lists, and the read-back.
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                    VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                    VK_ACCESS_2_TRANSFER_READ_BIT);
  return {};
}

void VisibleBricksPass::recordReadback(VkCommandBuffer cmd) {
  const VkDeviceSize bytes = visible_.size();
  const VkBufferCopy flags{0, 0, bytes};
  vkCmdCopyBuffer(cmd, visible_.handle(), readback_.handle(), 1, &flags);
  const VkBufferCopy commands{0, bytes, dispatch_.size()};
  vkCmdCopyBuffer(cmd, dispatch_.handle(), readback_.handle(), 1, &commands);
  const VkBufferCopy lists{0, bytes + dispatch_.size(), bytes};
  vkCmdCopyBuffer(cmd, lists_.handle(), readback_.handle(), 1, &lists);
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
}

std::vector<std::uint32_t> VisibleBricksPass::visibleFlags() const {
  std::vector<std::uint32_t> out(visible_.size() / sizeof(std::uint32_t));
  std::memcpy(out.data(), readback_.mapped(), visible_.size());
  return out;
}

std::vector<std::vector<std::uint32_t>> VisibleBricksPass::listedBricks() const {
  const auto* words = static_cast<const std::uint32_t*>(readback_.mapped());
  const std::size_t count = visible_.size() / sizeof(std::uint32_t);
  const std::uint32_t* commands = words + count;
  const std::uint32_t* lists = commands + 3 * bricks_.z;
  const std::size_t perLayer = static_cast<std::size_t>(bricks_.x) * bricks_.y;
  std::vector<std::vector<std::uint32_t>> out(bricks_.z);
  for (std::size_t layer = 0; layer < out.size(); ++layer)
    out[layer].assign(lists + layer * perLayer, lists + layer * perLayer + commands[3 * layer]);
  return out;
}

}  // namespace lic3d
