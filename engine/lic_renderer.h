#pragma once
// Ties the passes together for one field and one noise volume: keeps the LIC volume on the GPU,
// recomputes it only when LicParams, the field or the noise change, and draws it offscreen.

#include <cstdint>
#include <optional>

#include "error.h"
#include "gpu_resources.h"
#include "gpu_timer.h"
#include "lic_histogram.h"
#include "lic_params.h"
#include "lic_pass.h"
#include "lic_reference.h"
#include "rgba_image.h"
#include "slice_pass.h"
#include "view_params.h"
#include "volume.h"
#include "volume_textures.h"
#include "vulkan_context.h"

namespace lic3d {

// The offscreen colour buffer. 16-bit float (default) keeps hundreds of faint slices from
// banding; 8-bit UNORM halves the blending bandwidth.
enum class FramePrecision { Float16, Unorm8 };

struct RendererOptions {
  FieldPrecision fieldPrecision = FieldPrecision::Auto;
  FramePrecision framePrecision = FramePrecision::Float16;
  bool runtimeModes = false;  // benchmark builds only: see SlicePass::create
};

class LicRenderer {
 public:
  // `context` must outlive the renderer.
  static Result<LicRenderer> create(const Context& context, const RendererOptions& options = {});
  LicRenderer(LicRenderer&&) noexcept = default;
  LicRenderer& operator=(LicRenderer&&) noexcept = default;
  ~LicRenderer();

  // The field and the noise that LIC smears along it; they share one texture, so they are set
  // together (the noise must be on the field's grid).
  Result<void> setInputs(const VectorField& field, const NoiseVolume& noise);
  // Uses a LIC volume computed elsewhere (the CPU reference) as the result for `params`.
  Result<void> setLicVolume(const ScalarVolume& volume, const LicParams& params);

  // Runs the LIC pass unless the volume already matches `params`, the field and the noise.
  // With a progress callback the work is split into slabs along z, each submitted and waited
  // for, so long computations report progress (and hold the GPU in shorter pieces).
  // Returns whether the pass ran.
  Result<bool> updateLic(const LicParams& params, const ProgressCallback& progress = {});

  // updateLic, then one frame into an offscreen image read back as 8-bit RGBA. Side-by-side
  // stereo gives an image twice as wide (left eye | right eye); with a legend requested, the
  // colour legend is drawn into it.
  Result<RgbaImage> render(const LicParams& params, const ViewParams& view);

  // What frames are drawn from, for the current LIC volume.
  VolumeFacts volumeFacts() const;

  Result<ScalarVolume> readLicVolume() const;

  // Benchmark helpers: GPU milliseconds from timestamp queries around one LIC dispatch over the
  // whole volume (always dispatched), and around one frame's draw (no read-back).
  Result<double> timeLicDispatch(const LicParams& params);
  Result<double> timeFrame(const ViewParams& view);

  // The colour buffer's format for the next frames (see FramePrecision).
  Result<void> setFramePrecision(FramePrecision precision);

  std::uint64_t licDispatchCount() const { return licDispatches_; }
  std::uint64_t maskBuildCount() const { return maskBuilds_; }
  const IntensityStatistics& intensityStatistics() const { return statistics_; }
  Dims dims() const { return field_.dims; }
  const GridGeometry& geometry() const { return field_.geometry; }
  double fieldMaxMagnitude() const { return field_.maxMagnitude; }
  FieldPrecision fieldPrecision() const { return field_.precision; }
  const LicPass& licPass() const { return licPass_; }
  const SlicePass& slicePass() const { return slicePass_; }

 private:
  LicRenderer() = default;
  Result<void> ensureLicVolume();
  Result<void> ensureMask(const SparsityParams& sparsity);
  Result<void> ensureTarget(int width, int height);
  void recordLicSlab(VkCommandBuffer cmd, const LicParams& params, int zBegin, int zEnd,
                     bool first, bool last, Result<void>& status);
  void recordFrame(VkCommandBuffer cmd, const ViewParams& view, Result<void>& status);
  const Image& maskFor(const LicParams& params) const;

  const Context* context_ = nullptr;
  LicPass licPass_;
  LicHistogramPass histogramPass_;
  SlicePass slicePass_;
  GpuTimer timer_;  // region 0: LIC dispatch, region 1: frame
  FieldPrecision precision_ = FieldPrecision::Auto;
  VkFormat frameFormat_ = VK_FORMAT_R16G16B16A16_SFLOAT;
  FieldTexture field_;
  Image licVolume_;
  std::optional<LicParams> licParams_;  // what licVolume_ holds; empty when stale
  IntensityStatistics statistics_;
  std::uint64_t licDispatches_ = 0;
  Image mask_;           // the sparsity mask of maskParams_ on the field's grid
  Image emptyMask_;      // 1x1x1, bound when sparsity is off
  std::optional<SparsityParams> maskParams_;
  std::uint64_t maskBuilds_ = 0;
  Image target_;
  Buffer targetReadback_;
};

}  // namespace lic3d
