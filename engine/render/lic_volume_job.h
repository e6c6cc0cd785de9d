// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The LIC volume on the GPU and the job that recomputes it: a job starts for a LicParams, makes
// its sparsity mask on a worker thread and uploads it, records the LIC pass in slabs of z (one
// command buffer or many), then the volume's intensity histogram, whose statistics make it the
// shown volume. With doubleBuffered, the job writes a second volume, so a recompute spread over
// many frames never shows a half-written volume.
//
// A job may also make a coarse volume (stride 2, 4 or 8): every stride-th voxel along each axis,
// each the full LIC at that voxel (lic.comp's outputStride), written into a smaller image of its
// own that the slices sample through the same normalized coordinates (the picture shifts by at
// most about half a coarse voxel). It takes 1 / stride^3 of the work: what the app shows while a
// LIC parameter is dragged (coarseLicStride), replaced by the full volume when the drag ends.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <future>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/lic_params.h"
#include "core/volume.h"
#include "core/voxel_target.h"
#include "gpu/readback.h"
#include "gpu/resources.h"
#include "gpu/timer.h"
#include "gpu/vulkan_context.h"
#include "lic/lic_reference.h"
#include "lic/sparsity.h"
#include "passes/lic_histogram_pass.h"
#include "passes/lic_pass.h"
#include "passes/visible_bricks_pass.h"
#include "render/field_textures.h"
#include "render/sparsity_mask_store.h"

namespace lic3d {

// What one record() call did.
struct LicWork {
  int slicesRecorded = 0;  // z slices of the job's volume (of the coarse grid for a coarse job)
  int stride = 1;          // of the job recorded: 1 the full volume, > 1 a coarse one
  bool began = false;      // the job's first slice was recorded
  bool finished = false;   // the job's last slice was recorded: the new volume is shown
  bool waitingForMask = false;  // the sparsity mask is still being made on a worker thread
};

// Visible work takes the full pass when the bricks to make hold at least this share of the grid:
// the brick variant's launch (a brick slice per workgroup, the classification before it) then
// costs more than the voxels it leaves out (docs/VISIBLE_WORK.md, "Fallback").
inline constexpr double kVisibleFullPassShare = 0.9;

// What the last update with visible work did (docs/VISIBLE_WORK.md), in bricks of the grid.
struct VisibleWorkCounts {
  std::uint64_t bricks = 0;   // of the grid
  std::uint64_t visible = 0;  // by the last classification
  std::uint64_t made = 0;     // by the last update's LIC (0 when nothing new became visible)
  bool fullPass = false;      // the last LIC was the full pass (nearly every brick visible)
};

struct LicStatus {
  bool pending = false;   // a requested volume is not finished yet
  double fraction = 1.0;  // of the pending job's slices recorded
  bool waitingForMask = false;
  int stride = 1;  // of the pending job
};

// The LIC time a coarse job may take while a LIC parameter is dragged: what a 60 Hz frame
// (16.7 ms) leaves beside the slices' draw (7.7 ms for 256 slices at 1024^2 on the H100,
// docs/BENCHMARKS.md), rounded down.
inline constexpr double kDragLicBudgetMs = 8.0;
// The stride of the LIC while a LIC parameter is dragged: the smallest of 1, 2, 4 and 8 whose
// job, 1 / stride^3 of the work of a full LIC that took `fullLicMs`, fits in `budgetMs`
// (1 when no full LIC was timed: fullLicMs <= 0).
int coarseLicStride(double fullLicMs, double budgetMs = kDragLicBudgetMs);
// The stride after a coarse job at `stride` took `coarseMs`: twice it (up to 8) while it is over
// `budgetMs`. A coarse job costs more than 1 / stride^3 of the full one on a large grid: its
// streamlines start `stride` voxels apart, so neighbouring invocations share fewer texture
// cache lines (1024^3 at stride 4 took 47 ms on the H100 where 1/64 of the full LIC is 3 ms).
int nextCoarseStride(int stride, double coarseMs, double budgetMs = kDragLicBudgetMs);

class LicVolumeJob {
 public:
  LicVolumeJob() = default;
  // `context` must outlive the job. `naiveKernel` (benchmark builds only): the LIC pass reads the
  // noise from a texture of its own (FieldTextures' separateNoise). `launch` replaces the device
  // type's launch fields (licLaunchFor).
  // With `visibleWork` (single-buffered only), update() given a classification makes only the
  // visible bricks not made yet and takes the statistics of the visible bricks' voxels
  // (docs/VISIBLE_WORK.md); where the bricks to make after a change of the LIC hold at least
  // `fullPassShare` of the grid's voxels, it takes the full pass instead.
  static Result<LicVolumeJob> create(const Context& context, bool doubleBuffered,
                                     bool naiveKernel = false,
                                     std::optional<LicSpecialization> launch = std::nullopt,
                                     bool visibleWork = false,
                                     double fullPassShare = kVisibleFullPassShare);

  // A new field: the job and the shown volume are dropped, and with `newGrid` the mask and the
  // volumes too; `piece` is the field's place in the whole grid the mask is cut from. The caller
  // makes sure no work in flight reads them.
  void dropField(bool newGrid, const std::optional<FieldPiece>& piece);
  // The field texture changed under the shown volume: the next request recomputes it.
  void markFieldChanged() { fieldChanged_ = true; }
  // A field that is no piece of a larger grid on the same grid (a time series' blend).
  void forgetPiece() { piece_.reset(); }

  // Uses a volume computed elsewhere (the CPU reference) as the result for `params`.
  Result<void> setVolume(const ScalarVolume& volume, const LicParams& params,
                         const FieldTextures& textures);

  // Starts a job for `params` at `stride` (1: the full volume; 2, 4, 8: a coarse one) unless
  // the pending one is that (`force`: always); a new mask is made on a worker thread.
  Result<void> start(const LicParams& params, const FieldTextures& textures, bool force,
                     int stride = 1);
  // start() unless the shown or finished volume already has `params` at `stride` for the
  // current field.
  Result<void> request(const LicParams& params, const FieldTextures& textures, int stride = 1);
  // Waits for the pending job's sparsity mask and uploads it, so that record() records at once.
  Result<void> waitForMask(const FieldTextures& textures);
  // Records `maxSlices` z slices of the pending job (of its coarse grid for a coarse one), rounded
  // up to whole workgroups of the LIC pass; when it records the last one, the volume's histogram
  // goes to `slot`
  // (< LicHistogramPass::kSlots): call collectStatistics(slot) once `cmd` has completed. Until
  // then no further work is recorded.
  Result<LicWork> record(VkCommandBuffer cmd, const FieldTextures& textures, int maxSlices,
                         std::uint32_t slot);
  // Reads the histogram of `slot`; if it belongs to the finished volume, that volume and its
  // statistics are shown from then on.
  void collectStatistics(std::uint32_t slot);
  // Blocking: runs the pending or needed job to its end, in slabs with a progress callback.
  // Returns whether the LIC pass ran. With visible work and `visible`, the job makes the bricks
  // `visible` lists that are not made yet (all of them after a change of `params` or the field;
  // in slabs of brick layers) and the statistics become those of its visible bricks.
  Result<bool> update(const LicParams& params, const FieldTextures& textures,
                      const ProgressCallback& progress, const VisibleBricksSetup* visible = nullptr,
                      int stride = 1);
  // The shown volume read back on its grid: the field's, or the coarse grid of a coarse volume
  // (coarseDims, its spacing `stride` times the field's).
  Result<ScalarVolume> read(const FieldTextures& textures) const;
  // The region [from, from + extent) of the shown volume read back into `target` at `at` (the
  // region's first voxel in the target's grid), slab by slab through the job's staging ring
  // (gpu/readback.h), each slab converted on all threads while the device copies the next.
  // Returns how many of the region's voxels are drawn (all of them without a sparsity mask).
  Result<std::uint64_t> readInto(Dims from, Dims extent, const VoxelTarget& target, Dims at) const;
  // The staging bytes of the read-back ring, once it is made.
  std::size_t readbackBytes() const { return readback_.bytes(); }
  const ReadbackRing& readback() const { return readback_; }

  // Whether update(params) would run the pass: no full volume of `params` for the current field.
  bool needs(const LicParams& params) const {
    return job_ || !shownParams_ || !(*shownParams_ == params) || fieldChanged_ ||
           shownStride_ != 1;
  }
  // The same with visible work for the classification `visible`: also when the shown volume's
  // statistics or made bricks are of another classification.
  bool needs(const LicParams& params, const VisibleBricksSetup& visible) const {
    return needs(params) ||
           (visibleWork(params) && (!shownSetup_ || !sameClassification(*shownSetup_, visible)));
  }
  bool visibleWork() const { return visibleWork_; }
  // Whether a view makes only its visible bricks for `params`: not with a sparsity mask, whose
  // hidden fraction (the run summary's) is counted over the whole grid.
  bool visibleWork(const LicParams& params) const {
    return visibleWork_ && params.sparsity.distribution == SparsityDistribution::None;
  }
  const VisibleWorkCounts& visibleWorkCounts() const { return visibleCounts_; }
  LicStatus status(Dims dims) const;
  const Image& shownVolume() const { return volumes_[front_]; }
  const std::optional<LicParams>& shownParams() const { return shownParams_; }
  // 1 when the shown volume is the full one, else its stride; its grid for a field of `dims`.
  int shownStride() const { return shownStride_; }
  Dims shownDims(Dims dims) const { return coarseDims(dims, shownStride_); }
  const IntensityStatistics& statistics() const { return statistics_; }
  // The fraction of the voxels the shown volume's sparsity mask hid; nullopt without a mask.
  std::optional<double> hiddenFraction(Dims dims) const;
  std::uint64_t dispatchCount() const { return licDispatches_; }
  std::uint64_t maskBuildCount() const { return masks_.builds(); }
  // Of those, the masks taken from the cache of CPU-made masks (SparsityMaskStore).
  std::uint64_t maskCacheHits() const { return masks_.cacheHits(); }
  // Bytes of device memory the LIC volumes and the mask hold.
  std::uint64_t bytes() const;

  // The LIC pass' launch fields from now on (pipelines of every launch stay cached), and the
  // driver's statistics of the pipeline last used for `params` (LicPass::statistics).
  void setLaunch(const LicSpecialization& launch) { licPass_.setLaunch(launch); }
  std::vector<std::pair<std::string, std::string>> pipelineStatistics(
      const LicParams& params, FieldPrecision precision) const {
    return licPass_.statistics(params, precision);
  }
  std::size_t variantCount() const { return licPass_.variantCount(); }

 private:
  // The computation of one LIC volume, possibly spread over many command buffers.
  struct Job {
    LicParams params;
    int stride = 1;
    int nextZ = 0;  // of the job's grid
    bool needsMask = false;
    // Visible work: the classification; whether the made flags are cleared first (the LIC
    // values change); whether it ran; whether the LIC is over the listed bricks (nextZ then
    // steps by brick layers) or the full pass.
    std::optional<VisibleBricksSetup> visible;
    bool forget = true;
    bool classified = false;
    bool overBricks = false;
    bool nothingListed = false;
  };
  struct Finished {
    LicParams params;
    std::uint32_t slot = 0;                     // of the histogram to read
    std::optional<VisibleBricksSetup> visible;  // whose visible bricks the histogram counts
    int volume = 0;                             // which of volumes_ holds it
    int stride = 1;
  };

  // volumes_[index] on a grid of `dims`, made (again) if it has another extent.
  Result<void> ensureVolume(int index, Dims dims);
  // Which of volumes_ a job of `stride` writes.
  int backIndex(int stride) const;
  Result<bool> prepareMask(bool wait);
  const Buffer* maskFor(const LicParams& params) const;
  Result<void> classify(const FieldTextures& textures);
  Result<void> recordSlab(VkCommandBuffer cmd, const FieldTextures& textures, Image& back,
                          int zBegin, int zEnd);

  const Context* context_ = nullptr;
  mutable ReadbackRing readback_;  // made on the first read-back, kept for the next bricks
  LicPass licPass_;
  LicHistogramPass histogramPass_;
  bool doubleBuffered_ = false;
  // Full volumes in 0 and 1 (1 only doubleBuffered), coarse ones in 2 and 3: the shown one is
  // volumes_[front_], jobs write another.
  Image volumes_[4];
  int front_ = 0;
  std::optional<LicParams> shownParams_;  // what the shown volume holds; empty when none
  int shownStride_ = 1;
  std::optional<Job> job_;
  std::optional<Finished> finished_;  // computed, not shown until collectStatistics(slot)
  IntensityStatistics statistics_;
  std::uint64_t licDispatches_ = 0;
  SparsityMaskStore masks_;          // the sparsity mask on the field's grid
  std::optional<FieldPiece> piece_;  // of the field set, whose mask is cut from the whole grid's
  bool fieldChanged_ = false;        // the field texture changed under the shown LIC volume
  bool visibleWork_ = false;
  double fullPassShare_ = kVisibleFullPassShare;
  VisibleBricksPass bricks_;  // the made flags of volumes_[0] (visible work is single-buffered)
  // The classification of the shown volume's statistics; empty: the whole grid's (and the whole
  // volume made).
  std::optional<VisibleBricksSetup> shownSetup_;
  VisibleWorkCounts visibleCounts_;
};

// GPU milliseconds of one LIC dispatch over the whole volume of `params` (always dispatched;
// the volume is then shown), from region 0 of `timer`: what the benchmark and
// `compute --time-lic` measure.
Result<double> timeLicDispatch(const Context& context, LicVolumeJob& job,
                               const FieldTextures& textures, const GpuTimer& timer,
                               const LicParams& params);

}  // namespace lic3d
