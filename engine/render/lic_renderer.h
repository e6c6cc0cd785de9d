// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Ties the passes together for one field and one noise volume: keeps the LIC volume on the GPU,
// recomputes it only when LicParams, the field or the noise change, and draws it.
//
// Two ways to drive it:
// - blocking (CLI, tests, benchmark): updateLic() and render() record, submit and wait;
// - frame-paced (the desktop app): requestLic() names the wanted volume, recordLicWork() adds a
//   slab of the computation to each frame's command buffer, recordDraw() draws the last finished
//   volume. With doubleBuffered, a recompute spread over many frames never shows a half-written
//   volume, and a new request simply replaces the pending one (slider drags never queue up).

#include <cstdint>
#include <future>
#include <optional>
#include <string>

#include "core/error.h"
#include "core/lic_params.h"
#include "core/rgba_image.h"
#include "core/view_params.h"
#include "core/volume.h"
#include "gpu/resources.h"
#include "gpu/timer.h"
#include "gpu/vulkan_context.h"
#include "lic/legend.h"
#include "lic/lic_reference.h"
#include "lic/sparsity.h"
#include "passes/analytic_field_pass.h"
#include "passes/lic_histogram_pass.h"
#include "passes/lic_pass.h"
#include "passes/slice_pass.h"
#include "passes/time_blend_pass.h"
#include "passes/volume_textures.h"

namespace lic3d {

// The offscreen colour buffer. 16 bits per channel keep hundreds of faint slices from banding:
// float (the default) or UNORM, which holds [0, 1] (all blended colours lie there) with 16 bits
// everywhere; 8-bit UNORM halves the blending bandwidth; 10-bit UNORM colour (2-bit alpha, which
// stays 1 over the opaque background) has the 8-bit buffer's pixel size with 4x finer steps.
// Frame times: docs/BENCHMARKS.md.
enum class FramePrecision { Float16, Unorm16, Unorm10, Unorm8 };

struct RendererOptions {
  FieldPrecision fieldPrecision = FieldPrecision::Auto;
  FramePrecision framePrecision = FramePrecision::Float16;
  bool runtimeModes = false;    // benchmark builds only: see SlicePass::create
  bool doubleBuffered = false;  // a second LIC volume for frame-paced recomputes
  // Benchmark builds only: the LIC pass is the naive reference kernel (noise in an R8 texture of
  // its own, three fetches per exact RK2 sample), which `lic3d bench` compares the others with.
  bool naiveLicKernel = false;
  // Replaces the device type's workgroup shape and walk of the LIC pass (licLaunchFor).
  std::optional<LicSpecialization> licLaunch;
};

// What one recordLicWork() call did.
struct LicWork {
  int slicesRecorded = 0;
  bool finished = false;        // the job's last slice was recorded: the new volume is shown
  bool waitingForMask = false;  // the sparsity mask is still being made on a worker thread
};

struct LicStatus {
  bool pending = false;   // a requested volume is not finished yet
  double fraction = 1.0;  // of the pending job's slices recorded
  bool waitingForMask = false;
};

class LicRenderer {
 public:
  // `context` must outlive the renderer.
  static Result<LicRenderer> create(const Context& context, const RendererOptions& options = {});
  LicRenderer(LicRenderer&&) noexcept = default;
  LicRenderer& operator=(LicRenderer&&) noexcept = default;
  ~LicRenderer();

  // The field and the noise that LIC smears along it; they share one texture, so they are set
  // together (the noise must be on the field's grid). Waits for the device to be idle.
  Result<void> setInputs(const VectorField& field, const NoiseVolume& noise);
  // The same for an analytic field with white noise, made on the device straight into the field
  // texture (passes/analytic_field_pass.h): no host arrays at all. A texture of the same grid is
  // rewritten in place (a time animation of the tornado).
  Result<void> setAnalyticInputs(const AnalyticInputs& inputs);
  // What colour and opacity follow when not the speed (loading/scalars.h): scalars on the field's
  // grid, null for the speed. Kept until set again or until a field of another grid is set.
  // Redraws only; waits for the device to be idle.
  Result<void> setScalars(const PointScalars* color, const PointScalars* opacity);

  // Uses a LIC volume computed elsewhere (the CPU reference) as the result for `params`.
  Result<void> setLicVolume(const ScalarVolume& volume, const LicParams& params);

  // ---- Blocking use --------------------------------------------------------------------------

  // Runs the LIC pass unless the volume already matches `params`, the field and the noise.
  // With a progress callback the work is split into slabs along z, each submitted and waited
  // for, so long computations report progress (and hold the GPU in shorter pieces).
  // Returns whether the pass ran.
  Result<bool> updateLic(const LicParams& params, const ProgressCallback& progress = {});

  // updateLic, then one frame into an offscreen image read back as 8-bit RGBA. Side-by-side
  // stereo gives an image twice as wide (left eye | right eye); with a legend requested, the
  // colour legend is drawn into it.
  Result<RgbaImage> render(const LicParams& params, const ViewParams& view);

  Result<ScalarVolume> readLicVolume() const;
  // The LIC pass' workgroup shape and walk from now on (the benchmark's comparisons).
  void setLicLaunch(const LicSpecialization& launch) { licPass_.setLaunch(launch); }
  // The driver's statistics of the LIC pipeline last used for `params` (LicPass::statistics).
  std::vector<std::pair<std::string, std::string>> licPipelineStatistics(
      const LicParams& params) const {
    return licPass_.statistics(params, field_.precision);
  }

  // Benchmark helpers: GPU milliseconds from timestamp queries around one LIC dispatch over the
  // whole volume (always dispatched), and around one frame's draw (no read-back).
  Result<double> timeLicDispatch(const LicParams& params);
  Result<double> timeFrame(const ViewParams& view);

  // ---- Frame-paced use -------------------------------------------------------------------------

  // Asks for the volume of `params`. Nothing changes if the shown volume or the pending job
  // already has them; otherwise the pending job is dropped and a new one starts. A new sparsity
  // mask is made on a worker thread.
  Result<void> requestLic(const LicParams& params);
  // Records `maxSlices` z slices of the pending job, rounded up to whole workgroups of the LIC
  // pass (LicPass::launchDepth; the grid's end may cut the last). When it records the last one, the
  // volume's histogram goes to `slot` (< LicHistogramPass::kSlots): call collectStatistics(slot)
  // once `cmd` has completed. Until then no further work is recorded.
  Result<LicWork> recordLicWork(VkCommandBuffer cmd, int maxSlices, std::uint32_t slot);
  // Reads the histogram of `slot`; if it belongs to the finished volume, that volume and its
  // statistics are what recordDraw() draws from then on.
  void collectStatistics(std::uint32_t slot);
  // Records the shown volume's slices into an open dynamic rendering of one `format` attachment
  // into `area` of it (both halves of it for side-by-side stereo). Uniform slots `slotBase` and
  // slotBase + 1 must not be in use by a frame still in flight.
  Result<void> recordDraw(VkCommandBuffer cmd, VkFormat format, VkRect2D area,
                          const ViewParams& view, std::uint32_t slotBase);
  // The legend of `view` for the shown volume (colour on and a legend asked for), and where
  // render() puts the volume, the legend and the title in a picture of the view's size.
  std::optional<LegendSpec> legendFor(const ViewParams& view) const;
  PictureLayout pictureLayoutFor(const ViewParams& view) const;
  bool hasVolume() const { return shownParams_.has_value(); }
  // Whether updateLic(params) would run the pass: no volume of `params` for the current field.
  bool needsLic(const LicParams& params) const {
    return job_ || !shownParams_ || !(*shownParams_ == params) || fieldChanged_;
  }
  LicStatus licStatus() const;

  // ---- Unsteady fields (docs/TIME.md) -----------------------------------------------------------
  // A time series keeps two of its steps resident and makes the field texture from them on the
  // GPU (TimeBlendPass). A new field recomputes the LIC volume at the next updateLic or
  // requestLic; the shown volume stays until then, so a time slider never blanks the picture.

  // Starts a series: its noise, on the steps' grid, set before the first blendTime. The
  // steps resident from an earlier series are dropped.
  Result<void> setTimeNoise(const NoiseVolume& noise);
  // Uploads `step` as step `index` of the series into the resident slot that does not hold step
  // `keep` (the other step in use): only two steps are ever on the device.
  Result<void> setTimeStep(int index, const VectorField& step, int keep);
  bool hasTimeStep(int index) const;
  // The field becomes (1 - w) step `first` + w step `second`, both resident.
  Result<void> blendTime(int first, int second, double weight);
  // GPU milliseconds of the last blend (0 before any or without timestamp queries).
  double lastBlendMilliseconds() const {
    return interpolation_ ? interpolation_->lastMilliseconds() : 0.0;
  }

  // ---- State ------------------------------------------------------------------------------------

  // What frames are drawn from, for the shown LIC volume.
  VolumeFacts volumeFacts() const;

  // The colour buffer's format for the next offscreen frames (see FramePrecision).
  Result<void> setFramePrecision(FramePrecision precision);

  // The Vulkan device's name ("NVIDIA H100 80GB HBM3", "llvmpipe (LLVM 15.0.6, 256 bits)").
  const std::string& deviceName() const { return context_->deviceInfo().name; }
  std::uint64_t licDispatchCount() const { return licDispatches_; }
  std::uint64_t maskBuildCount() const { return maskBuilds_; }
  const IntensityStatistics& intensityStatistics() const { return statistics_; }
  // The fraction of the voxels the shown volume's sparsity mask hid (the histogram pass' count of
  // masked voxels; its drawn fraction leaves out empty space too); nullopt without a mask.
  std::optional<double> hiddenFraction() const;
  Dims dims() const { return field_.dims; }
  const GridGeometry& geometry() const { return field_.geometry; }
  double fieldMaxMagnitude() const { return field_.maxMagnitude; }
  FieldPrecision fieldPrecision() const { return field_.precision; }
  const std::optional<LicParams>& shownParams() const { return shownParams_; }
  // Bytes of device memory the renderer's volumes hold (field, LIC volumes, mask).
  std::uint64_t volumeBytes() const;
  const LicPass& licPass() const { return licPass_; }
  const SlicePass& slicePass() const { return slicePass_; }

 private:
  // The computation of one LIC volume, possibly spread over many command buffers.
  struct Job {
    LicParams params;
    int nextZ = 0;
    bool needsMask = false;
    std::shared_future<Result<SparsityMask>> mask;
  };

  LicRenderer() = default;
  // What any new field resets (the job, the shown volume, a series' steps; the mask, the
  // volumes and the scalars of another grid or piece). Waits for the device to be idle.
  Result<void> replaceField(Dims dims, const std::optional<FieldPiece>& piece);
  Result<void> ensureVolumes();
  Result<void> startJob(const LicParams& params, bool force);
  Result<bool> prepareMask();
  Result<void> uploadMask(const SparsityMask& mask);
  Result<void> ensureScalarTexture();
  // Physical |v| below which voxels are empty space, left out of the LIC histogram: a fraction
  // kEmptySpeedFraction of the field's fast speeds (core/look.h).
  double emptySpeed() const;
  Result<void> ensureTarget(int width, int height);
  void recordOffscreenFrame(VkCommandBuffer cmd, const ViewParams& view, Result<void>& status);
  const Image& maskFor(const LicParams& params) const;
  Image& backVolume() { return volumes_[doubleBuffered_ ? 1 - front_ : front_]; }
  const Image& frontVolume() const { return volumes_[front_]; }

  const Context* context_ = nullptr;
  LicPass licPass_;
  LicHistogramPass histogramPass_;
  SlicePass slicePass_;
  GpuTimer timer_;  // region 0: LIC dispatch, region 1: frame
  FieldPrecision precision_ = FieldPrecision::Auto;
  VkFormat frameFormat_ = VK_FORMAT_R16G16B16A16_SFLOAT;
  bool doubleBuffered_ = false;
  FieldTexture field_;
  Image separateNoise_;  // R8, only for the naive kernel
  Image volumes_[2];     // the shown one is volumes_[front_]; the other is written by jobs
  int front_ = 0;
  std::optional<LicParams> shownParams_;  // what the shown volume holds; empty when none
  std::optional<Job> job_;
  struct Finished {
    LicParams params;
    std::uint32_t slot = 0;  // of the histogram to read
  };
  std::optional<Finished> finished_;  // computed, not shown until collectStatistics(slot)
  IntensityStatistics statistics_;
  std::uint64_t licDispatches_ = 0;
  Image mask_;             // the sparsity mask of maskParams_ on the field's grid
  Image emptyMask_;        // 1x1x1, bound when sparsity is off
  ScalarTexture scalars_;  // colour and opacity scalars (1x1x1 while both follow the speed)
  std::optional<SparsityParams> maskParams_;
  MaskBeyondGrid maskBeyond_;        // of mask_
  std::optional<FieldPiece> piece_;  // of the field set, whose mask is cut from the whole grid's
  std::uint64_t maskBuilds_ = 0;
  // Unsteady fields: the pass, the two resident steps and what the field texture was made from.
  std::optional<TimeBlendPass> interpolation_;
  FieldStep timeSteps_[2];
  struct TimeKey {
    int first, second;
    double weight;
    bool operator==(const TimeKey&) const = default;
  };
  std::optional<TimeKey> interpolated_;
  bool fieldChanged_ = false;  // the field texture changed under the shown LIC volume
  bool timeTexture_ = false;   // field_ is written by interpolation_ (not uploaded)
  std::optional<AnalyticFieldPass> analytic_;
  bool analyticTexture_ = false;  // field_ is written by analytic_ (not uploaded)
  Image target_;
  Buffer targetReadback_;
};

}  // namespace lic3d
