// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The graphics pass: alpha-blended slice proxies through the LIC volume, back to front, into
// whatever colour attachment the caller's dynamic rendering has open. Display variants (colour,
// opacity, sparsity, region of interest, fog, lighting, halos, occlusion, jitter, filtering,
// anaglyph eye) are specialization constants; one pipeline per (variant, attachment format),
// made on first use and cached. With occlusion the slices are drawn front to back before the
// frame's rendering (prepare) and composited inside it (record).

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

#include "core/camera.h"
#include "core/error.h"
#include "core/slice_geometry.h"
#include "core/view_params.h"
#include "gpu/pipelines.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"
#include "passes/occlusion_pass.h"
#include "passes/volume_textures.h"
#include "shared_layout.h"

namespace lic3d {

// constant_id i <-> field i (see shaders/slice.frag), each defaulting to the shader's default
// (shared_layout.h).
struct SliceSpecialization {
  std::uint32_t opacityMode = gpu::kSliceDefaultOpacityMode;
  std::uint32_t orthographic = gpu::kSliceDefaultOrthographic;
  std::uint32_t colorMode = gpu::kSliceDefaultColorMode;
  std::uint32_t colormap = gpu::kSliceDefaultColormap;
  std::uint32_t magnitudeOpacity = gpu::kSliceDefaultMagnitudeOpacity;
  std::uint32_t sparsity = gpu::kSliceDefaultSparsity;
  std::uint32_t roiShape = gpu::kSliceDefaultRoiShape;
  std::uint32_t roiOutside = gpu::kSliceDefaultRoiOutside;
  std::uint32_t fog = gpu::kSliceDefaultFog;
  std::uint32_t lighting = gpu::kSliceDefaultLighting;
  std::uint32_t filter = gpu::kSliceDefaultFilter;
  std::uint32_t anaglyph = gpu::kSliceDefaultAnaglyph;
  std::uint32_t fieldPacking = gpu::kSliceDefaultFieldPacking;  // LicSpecialization::packing
  std::uint32_t opacityTable = gpu::kSliceDefaultOpacityTable;  // the transfer function's opacities
  std::uint32_t clipPlane = gpu::kSliceDefaultClipPlane;
  // 1: the scalar texture's R (ScalarTexture::color)
  std::uint32_t colorSource = gpu::kSliceDefaultColorSource;
  std::uint32_t opacitySource = gpu::kSliceDefaultOpacitySource;  // 1: its G
  std::uint32_t halo = gpu::kSliceDefaultHalo;
  std::uint32_t occlusion = gpu::kSliceDefaultOcclusion;  // drawn front to back (OcclusionPass)
  std::uint32_t jitter = gpu::kSliceDefaultJitter;
  // Not a display mode: K slices composited per fragment (SlicePass::slicesPerFragment).
  std::uint32_t slicesPerFragment = gpu::kSliceDefaultSlicesPerFragment;

  bool operator==(const SliceSpecialization&) const = default;
};
static_assert(sizeof(SliceSpecialization) == 21 * 4);
static_assert(offsetof(SliceSpecialization, opacityMode) == 4 * gpu::kSliceConstOpacityMode);
static_assert(offsetof(SliceSpecialization, orthographic) == 4 * gpu::kSliceConstOrthographic);
static_assert(offsetof(SliceSpecialization, colorMode) == 4 * gpu::kSliceConstColorMode);
static_assert(offsetof(SliceSpecialization, colormap) == 4 * gpu::kSliceConstColormap);
static_assert(offsetof(SliceSpecialization, magnitudeOpacity) ==
              4 * gpu::kSliceConstMagnitudeOpacity);
static_assert(offsetof(SliceSpecialization, sparsity) == 4 * gpu::kSliceConstSparsity);
static_assert(offsetof(SliceSpecialization, roiShape) == 4 * gpu::kSliceConstRoiShape);
static_assert(offsetof(SliceSpecialization, roiOutside) == 4 * gpu::kSliceConstRoiOutside);
static_assert(offsetof(SliceSpecialization, fog) == 4 * gpu::kSliceConstFog);
static_assert(offsetof(SliceSpecialization, lighting) == 4 * gpu::kSliceConstLighting);
static_assert(offsetof(SliceSpecialization, filter) == 4 * gpu::kSliceConstFilter);
static_assert(offsetof(SliceSpecialization, anaglyph) == 4 * gpu::kSliceConstAnaglyph);
static_assert(offsetof(SliceSpecialization, fieldPacking) == 4 * gpu::kSliceConstFieldPacking);
static_assert(offsetof(SliceSpecialization, opacityTable) == 4 * gpu::kSliceConstOpacityTable);
static_assert(offsetof(SliceSpecialization, clipPlane) == 4 * gpu::kSliceConstClipPlane);
static_assert(offsetof(SliceSpecialization, colorSource) == 4 * gpu::kSliceConstColorSource);
static_assert(offsetof(SliceSpecialization, opacitySource) == 4 * gpu::kSliceConstOpacitySource);
static_assert(offsetof(SliceSpecialization, halo) == 4 * gpu::kSliceConstHalo);
static_assert(offsetof(SliceSpecialization, occlusion) == 4 * gpu::kSliceConstOcclusion);
static_assert(offsetof(SliceSpecialization, jitter) == 4 * gpu::kSliceConstJitter);
static_assert(offsetof(SliceSpecialization, slicesPerFragment) ==
              4 * gpu::kSliceConstSlicesPerFragment);

// What a frame needs to know about the volume besides the view.
struct VolumeFacts {
  Dims dims{1};
  GridGeometry geometry;
  float minMagnitude = 0.0f;  // physical |v| over the grid's voxels (the automatic colour range)
  float maxMagnitude = 1.0f;
  glm::vec3 texelToPhysical{1.0f};  // FieldTexture::texelToPhysical: decodes the field texture
  float intensityMean = 0.5f;       // of the drawn voxels' LIC values
  float intensityDeviation = 0.1f;  // their standard deviation
  bool sparsity = false;            // the LIC volume carries a sparsity mask
  FieldPrecision fieldPrecision = FieldPrecision::Half;  // how the field texture is packed

  // What automatic ranges, windows and alpha are measured on (TransferFacts).
  std::shared_ptr<const ValueHistogram> intensities;
  std::shared_ptr<const ValueHistogram> colorValues;
  std::shared_ptr<const ValueHistogram> opacityValues;
  float drawnFraction = 1.0f;
  // Colour and opacity by a scalar texture instead of |v| (ScalarTexture), its value range, and
  // what the legend calls the colour scalar.
  bool colorScalar = false;
  bool opacityScalar = false;
  glm::vec4 scalarRange{0.0f, 1.0f, 0.0f, 1.0f};
  std::string colorName = "speed";
  std::string colorUnit;

  TransferFacts transfer() const {
    return {intensityMean, intensityDeviation, minMagnitude,  maxMagnitude,
            intensities,   colorValues,        opacityValues, drawnFraction};
  }
};

// Which eye a draw is for: stereo offsets the camera by half the eye separation.
enum class Eye { Mono, Left, Right };

// Everything one draw needs, derived from ViewParams and VolumeFacts.
struct SliceFrame {
  SliceSpecialization specialization;
  gpu::SliceUniforms uniforms{};
  CameraMatrices camera;
  SlicePlan plan;
  glm::vec3 halfExtent{0.5f};
  int eyeIndex = 0;  // 0 mono or left, 1 right: whose occlusion images
  // Whether slices may be drawn K to a fragment: the clip box lies wholly between the camera's
  // near and far planes, so no slice is cut by them (slice.vert's group proxies are not).
  bool groupable = false;
};

// `viewport` is the eye's size in pixels.
SliceFrame makeSliceFrame(const ViewParams& view, const VolumeFacts& volume, Eye eye,
                          VkExtent2D viewport);

// Eye separation and zero-parallax distance after defaults (world units).
float eyeSeparation(const ViewParams& view, const CameraMatrices& central);
float zeroParallaxDistance(const ViewParams& view, const CameraMatrices& central);

class SlicePass {
 public:
  // Uniform slots: a draw's parameters live in one slot until its command buffer completes.
  static constexpr std::uint32_t kUniformSlots = 8;

  // `context` must outlive the pass. With `runtimeModes` (benchmark builds only) every display
  // mode is decided at run time by one shader instead of by specialization. With
  // `haloPipelinePerSlice`, on a CPU driver the slices that draw no halo take the pipeline without
  // the ring, one draw per slice (pipelineWithoutHalo).
  static Result<SlicePass> create(const Context& context, bool runtimeModes = false,
                                  bool haloPipelinePerSlice = true);

  // Outside any rendering, before record(): what must be drawn before the frame's rendering
  // opens (the occlusion variant's front-to-back slices; nothing for the others). The same
  // arguments as record's.
  Result<void> prepare(VkCommandBuffer cmd, VkRect2D viewport, const Image& volume,
                       const FieldTexture& field, const Image& scalars, const SliceFrame& frame,
                       std::uint32_t slot);

  // Records the draw inside an open dynamic rendering of one `colorFormat` attachment, into
  // `viewport` of it. `volume` and `field.image` must be in SHADER_READ_ONLY_OPTIMAL with their
  // writes visible to fragment shaders. `slot` must not be used by a draw still in flight.
  Result<void> record(VkCommandBuffer cmd, VkFormat colorFormat, VkRect2D viewport,
                      const Image& volume, const FieldTexture& field, const Image& scalars,
                      const SliceFrame& frame, std::uint32_t slot);

  // The transfer function's row of the colour table (core/colormap.h): uploaded when it changed.
  Result<void> setTransferFunction(const TransferFunction& tf, Colormap map);

  std::size_t variantCount() const { return pipelines_.size(); }

  // K, the slices one fragment composites: 1, 2 or 4, or 0 for the device's choice
  // (kSlicesPerFragmentGpu, kSlicesPerFragmentCpu). Pictures are the same whatever K but for the
  // rounding of the blend; K > 1 blends 1/K as often. Neither device type gains: the H100's
  // frame is bound by its fragment rate, not the blend (K = 2 took 13.0 ms where K = 1 took 7.7),
  // and a CPU driver's cost is the samples shaded, a group's samples outside the box as well
  // (docs/BENCHMARKS.md). Both keep K = 1; K > 1 stays for devices that blend slowly.
  void setSlicesPerFragment(int k) { requestedSlicesPerFragment_ = k; }
  // What a frame is drawn with: 1 with occlusion (each slice reads the buffer the one in front
  // wrote, blurred) or where the frame is not groupable, else the requested K.
  std::uint32_t slicesPerFragment(const SliceFrame& frame) const;
  static constexpr int kSlicesPerFragmentGpu = 1;
  static constexpr int kSlicesPerFragmentCpu = 1;

 private:
  // A pipeline per display variant and colour attachment format.
  struct SliceVariant {
    SliceSpecialization specialization;
    VkFormat format = VK_FORMAT_UNDEFINED;
    bool operator==(const SliceVariant&) const = default;
  };
  Result<Pipeline> createPipeline(const SliceVariant& variant) const;
  Result<VkPipeline> pipelineFor(const SliceFrame& frame, VkFormat format);
  // The pipeline for the slices that draw no halo: `pipelineFor` unless a CPU driver draws halos.
  Result<VkPipeline> pipelineWithoutHalo(const SliceFrame& frame, VkFormat format);
  void writeUniforms(const gpu::SliceUniforms& uniforms, std::uint32_t slot) const;
  void pushDescriptors(VkCommandBuffer cmd, const Image& volume, const FieldTexture& field,
                       const Image& scalars, VkImageView occlusion, std::uint32_t slot) const;

  const Context* context_ = nullptr;
  bool runtimeModes_ = false;
  bool haloPipelinePerSlice_ = true;
  int requestedSlicesPerFragment_ = 0;
  PipelineLayout layout_;
  ShaderModule vertexShader_;
  ShaderModule fragmentShader_;
  Sampler linear_;
  Image colormaps_;
  TransferFunction tableTransfer_;  // what the table's custom row holds
  Colormap tableMap_ = Colormap::Thesis;
  Buffer uniforms_;
  VkDeviceSize slotSize_ = 0;
  PipelineCache<SliceVariant> pipelines_;
  OcclusionPass occlusion_;
};

}  // namespace lic3d
