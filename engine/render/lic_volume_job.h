// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The LIC volume on the GPU and the job that recomputes it: a job starts for a LicParams, makes
// its sparsity mask on a worker thread and uploads it, records the LIC pass in slabs of z (one
// command buffer or many), then the volume's intensity histogram, whose statistics make it the
// shown volume. With doubleBuffered, the job writes a second volume, so a recompute spread over
// many frames never shows a half-written volume.

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
  int slicesRecorded = 0;
  bool finished = false;        // the job's last slice was recorded: the new volume is shown
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
};

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

  // Starts a job for `params` unless the pending one has them (`force`: always); a new mask is
  // made on a worker thread.
  Result<void> start(const LicParams& params, const FieldTextures& textures, bool force);
  // start() unless the shown or finished volume already has `params` for the current field.
  Result<void> request(const LicParams& params, const FieldTextures& textures);
  // Waits for the pending job's sparsity mask and uploads it, so that record() records at once.
  Result<void> waitForMask(const FieldTextures& textures);
  // Records `maxSlices` z slices of the pending job, rounded up to whole workgroups of the LIC
  // pass; when it records the last one, the volume's histogram goes to `slot`
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
                      const ProgressCallback& progress,
                      const VisibleBricksSetup* visible = nullptr);
  // The shown volume read back on the field's grid.
  Result<ScalarVolume> read(const FieldTextures& textures) const;

  // Whether update(params) would run the pass: no volume of `params` for the current field.
  bool needs(const LicParams& params) const {
    return job_ || !shownParams_ || !(*shownParams_ == params) || fieldChanged_;
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
    int nextZ = 0;
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
  };

  Result<void> ensureVolumes(const FieldTextures& textures);
  Result<bool> prepareMask(bool wait);
  const Buffer* maskFor(const LicParams& params) const;
  Image& backVolume() { return volumes_[doubleBuffered_ ? 1 - front_ : front_]; }
  Result<void> classify(const FieldTextures& textures);
  Result<void> recordSlab(VkCommandBuffer cmd, const FieldTextures& textures, Image& back,
                          int zBegin, int zEnd);

  const Context* context_ = nullptr;
  LicPass licPass_;
  LicHistogramPass histogramPass_;
  bool doubleBuffered_ = false;
  Image volumes_[2];  // the shown one is volumes_[front_]; the other is written by jobs
  int front_ = 0;
  std::optional<LicParams> shownParams_;  // what the shown volume holds; empty when none
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
