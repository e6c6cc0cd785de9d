// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Ties the parts together for one field and one noise volume: the field textures
// (render/field_textures.h), the LIC volume and the job that recomputes it only when LicParams,
// the field or the noise change (render/lic_volume_job.h), the slices that draw it, and the
// offscreen target blocking renders go to (render/offscreen_target.h).
//
// Two ways to drive it:
// - blocking (CLI, tests, benchmark): updateLic() and render() record, submit and wait;
// - frame-paced (the desktop app): requestLic() names the wanted volume, recordLicWork() adds a
//   slab of the computation to each frame's command buffer, recordDraw() draws the last finished
//   volume. With doubleBuffered, a recompute spread over many frames never shows a half-written
//   volume, and a new request simply replaces the pending one (slider drags never queue up).

#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <string>

#include "core/error.h"
#include "core/lic_params.h"
#include "core/rgba_image.h"
#include "core/view_params.h"
#include "core/volume.h"
#include "gpu/vulkan_context.h"
#include "lic/legend.h"
#include "passes/slice_pass.h"
#include "render/field_textures.h"
#include "render/lic_volume_job.h"
#include "render/offscreen_target.h"

namespace lic3d {

struct RendererOptions {
  FieldPrecision fieldPrecision = FieldPrecision::Auto;
  FramePrecision framePrecision = FramePrecision::Float16;
  bool runtimeModes = false;    // benchmark builds only: see SlicePass::create
  bool doubleBuffered = false;  // a second LIC volume for frame-paced recomputes
  // On a CPU driver, the slices without halos take a pipeline of their own, one draw per slice
  // (SlicePass::create). The app keeps one draw: on lavapipe the draws per frame grew the driver's
  // memory for hundreds of frames, past the soak's tolerance.
  bool haloPipelinePerSlice = true;
  // K slices composited per fragment, 1, 2 or 4; 0: the device's choice (SlicePass).
  int slicesPerFragment = 0;
  // Benchmark builds only: the LIC pass is the naive reference kernel (noise in an R8 texture of
  // its own, three fetches per exact RK2 sample), which `lic3d bench` compares the others with.
  bool naiveLicKernel = false;
  // Replaces the device type's workgroup shape and walk of the LIC pass (licLaunchFor).
  std::optional<LicSpecialization> licLaunch;
  // Visible work (docs/VISIBLE_WORK.md): a LIC update given a view makes only the bricks it can
  // show, and the contrast stretch follows their voxels. Pictures only: a LIC volume that is
  // written out (`compute`) needs every voxel. Not with doubleBuffered or naiveLicKernel.
  bool visibleWork = false;
  // The share of the grid's voxels in visible bricks from which the full pass is taken instead
  // (0: always, with the visible bricks' statistics; above 1: never).
  double visibleFullPassShare = kVisibleFullPassShare;
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
  // What colour and opacity follow when not the speed (loading/scalars.h): scalars on the
  // field's grid, null for the speed. Kept until set again or until a field of another grid is
  // set. Redraws only; waits for the device to be idle.
  Result<void> setScalars(const PointScalars* color, const PointScalars* opacity);

  // Uses a LIC volume computed elsewhere (the CPU reference) as the result for `params`.
  Result<void> setLicVolume(const ScalarVolume& volume, const LicParams& params);

  // ---- Blocking use --------------------------------------------------------------------------

  // Runs the LIC pass unless the volume already matches `params`, the field and the noise.
  // With a progress callback the work is split into slabs along z, each submitted and waited
  // for, so long computations report progress (and hold the GPU in shorter pieces).
  // Returns whether the pass ran.
  Result<bool> updateLic(const LicParams& params, const ProgressCallback& progress = {});
  // The same for pictures of `view`: with visible work, only the bricks `view` can show that are
  // not made yet are made (every visible brick after a change of `params`, the field or the
  // noise), and the statistics are those of the visible bricks; without, updateLic(params).
  Result<bool> updateLic(const LicParams& params, const ViewParams& view,
                         const ProgressCallback& progress = {});

  // updateLic, then one frame into an offscreen image read back as 8-bit RGBA. Side-by-side
  // stereo gives an image twice as wide (left eye | right eye); with a legend requested, the
  // colour legend is drawn into it.
  Result<RgbaImage> render(const LicParams& params, const ViewParams& view);

  Result<ScalarVolume> readLicVolume() const { return job_.read(textures_); }
  // The region [from, from + extent) of the LIC volume into `target` at `at`
  // (LicVolumeJob::readInto); returns the region's drawn voxels.
  Result<std::uint64_t> readLicInto(Dims from, Dims extent, const VoxelTarget& target,
                                    Dims at) const {
    return job_.readInto(from, extent, target, at);
  }

  // Records one frame of the shown volume into `target` (sized for the view): its cleared
  // rendering and the draw into the picture's part of it; the read-back is the caller's.
  Result<void> recordFrame(VkCommandBuffer cmd, const OffscreenTarget& target,
                           const ViewParams& view);

  // ---- Frame-paced use -------------------------------------------------------------------------

  // Asks for the volume of `params`. Nothing changes if the shown volume or the pending job
  // already has them; otherwise the pending job is dropped and a new one starts. A new sparsity
  // mask is made on a worker thread. `stride` > 1 asks for a coarse volume instead
  // (render/lic_volume_job.h): what a LIC slider's drag shows.
  Result<void> requestLic(const LicParams& params, int stride = 1) {
    return job_.request(params, textures_, stride);
  }
  // Records `maxSlices` z slices of the pending job (LicVolumeJob::record); call
  // collectStatistics(slot) once `cmd` has completed.
  Result<LicWork> recordLicWork(VkCommandBuffer cmd, int maxSlices, std::uint32_t slot) {
    return job_.record(cmd, textures_, maxSlices, slot);
  }
  // Reads the histogram of `slot`; if it belongs to the finished volume, that volume and its
  // statistics are what recordDraw() draws from then on.
  void collectStatistics(std::uint32_t slot) { job_.collectStatistics(slot); }
  // Records what must precede the frame's rendering (occlusion shading draws the slices front to
  // back into images of its own): call it outside any rendering, then recordDraw with the same
  // arguments.
  Result<void> prepareDraw(VkCommandBuffer cmd, VkRect2D area, const ViewParams& view,
                           std::uint32_t slotBase);
  // Records the shown volume's slices into an open dynamic rendering of one `format` attachment
  // into `area` of it (both halves of it for side-by-side stereo). Uniform slots `slotBase` and
  // slotBase + 1 must not be in use by a frame still in flight.
  Result<void> recordDraw(VkCommandBuffer cmd, VkFormat format, VkRect2D area,
                          const ViewParams& view, std::uint32_t slotBase);
  // The legend of `view` for the shown volume (colour on and a legend asked for), and where
  // render() puts the volume, the legend and the title in a picture of the view's size.
  std::optional<LegendSpec> legendFor(const ViewParams& view) const;
  PictureLayout pictureLayoutFor(const ViewParams& view) const;
  bool hasVolume() const { return job_.shownParams().has_value(); }
  // Whether updateLic(params) would run the pass: no volume of `params` for the current field.
  bool needsLic(const LicParams& params) const { return job_.needs(params); }
  // Whether updateLic(params, view) would run a pass (LIC, classification or statistics).
  Result<bool> needsLic(const LicParams& params, const ViewParams& view) const;
  // The classification of the bricks `view` can show (both eyes of a stereo view); nullopt
  // without visible work or before a field is set.
  Result<std::optional<VisibleBricksSetup>> visibleBricksFor(const ViewParams& view) const;
  // What the last update with visible work made and left out.
  const VisibleWorkCounts& visibleWorkCounts() const { return job_.visibleWorkCounts(); }
  LicStatus licStatus() const { return job_.status(textures_.field().dims); }

  // ---- Unsteady fields (docs/TIME.md) -----------------------------------------------------------
  // A time series keeps two of its steps resident and makes the field texture from them on the
  // GPU (TimeBlendPass). A new field recomputes the LIC volume at the next updateLic or
  // requestLic; the shown volume stays until then, so a time slider never blanks the picture.

  // Starts a series: its noise, on the steps' grid, set before the first blendTime. The
  // steps resident from an earlier series are dropped.
  Result<void> setTimeNoise(const NoiseVolume& noise) { return textures_.setTimeNoise(noise); }
  // Uploads `step` as step `index` of the series into the resident slot that does not hold step
  // `keep` (the other step in use): only two steps are ever on the device.
  Result<void> setTimeStep(int index, const VectorField& step, int keep) {
    return textures_.setTimeStep(index, step, keep);
  }
  bool hasTimeStep(int index) const { return textures_.hasTimeStep(index); }
  // The field becomes (1 - w) step `first` + w step `second`, both resident.
  Result<void> blendTime(int first, int second, double weight);
  // GPU milliseconds of the last blend (0 before any or without timestamp queries).
  double lastBlendMilliseconds() const { return textures_.lastBlendMilliseconds(); }

  // ---- State ------------------------------------------------------------------------------------

  // What frames are drawn from, for the shown LIC volume.
  VolumeFacts volumeFacts() const;

  // The colour buffer's format for the next offscreen frames (see FramePrecision).
  Result<void> setFramePrecision(FramePrecision precision) {
    return target_.setPrecision(precision);
  }

  // The Vulkan device's name ("NVIDIA H100 80GB HBM3", "llvmpipe (LLVM 15.0.6, 256 bits)").
  const std::string& deviceName() const { return context_->deviceInfo().name; }
  std::uint64_t licDispatchCount() const { return job_.dispatchCount(); }
  std::uint64_t maskBuildCount() const { return job_.maskBuildCount(); }
  std::uint64_t maskCacheHits() const { return job_.maskCacheHits(); }
  const IntensityStatistics& intensityStatistics() const { return job_.statistics(); }
  // The fraction of the voxels the shown volume's sparsity mask hid (the histogram pass' count of
  // masked voxels; its drawn fraction leaves out empty space too); nullopt without a mask.
  std::optional<double> hiddenFraction() const {
    return job_.hiddenFraction(textures_.field().dims);
  }
  Dims dims() const { return textures_.field().dims; }
  const GridGeometry& geometry() const { return textures_.field().geometry; }
  double fieldMaxMagnitude() const { return textures_.field().maxMagnitude; }
  FieldPrecision fieldPrecision() const { return textures_.field().precision; }
  const std::optional<LicParams>& shownParams() const { return job_.shownParams(); }
  // Bytes of device memory the renderer's volumes hold (field, LIC volumes, mask).
  std::uint64_t volumeBytes() const { return textures_.bytes() + job_.bytes(); }

  // The parts, for work recorded and timed outside (the benchmark, bricks' --time-lic).
  LicVolumeJob& licJob() { return job_; }
  const LicVolumeJob& licJob() const { return job_; }
  const FieldTextures& fieldTextures() const { return textures_; }
  std::size_t drawVariantCount() const { return slicePass_.variantCount(); }
  // SlicePass::setSlicesPerFragment: 1, 2 or 4 slices composited per fragment, 0 automatic.
  void setSlicesPerFragment(int k) { slicePass_.setSlicesPerFragment(k); }

 private:
  LicRenderer() = default;
  // What any new field resets (the job, the shown volume, a series' steps; the mask, the
  // volumes and the scalars of another grid or piece). Waits for the device to be idle.
  Result<void> replaceField(Dims dims, const std::optional<FieldPiece>& piece);

  const Context* context_ = nullptr;
  FieldTextures textures_;
  LicVolumeJob job_;
  // One slice draw per eye of `view` in `area`.
  struct EyeDraw {
    SliceFrame frame;
    VkRect2D viewport{};
  };
  std::vector<EyeDraw> eyeDraws(VkRect2D area, const ViewParams& view) const;
  // eyeDraws of the view as drawn (validated, a signed scalar's map), its colour table uploaded.
  Result<std::vector<EyeDraw>> shownDraws(VkRect2D area, const ViewParams& given);

  SlicePass slicePass_;
  OffscreenTarget target_;
};

}  // namespace lic3d
