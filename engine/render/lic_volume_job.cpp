// SPDX-License-Identifier: BSD-3-Clause
#include "render/lic_volume_job.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>

#include "core/parallel.h"
#include "core/stage_times.h"
#include "gpu/submit.h"

namespace lic3d {
namespace {
using Clock = std::chrono::steady_clock;
}  // namespace
namespace {

// With progress reporting the pass is split into this many slabs along z (at most).
constexpr int kProgressSlabs = 16;

constexpr int kBrick = static_cast<int>(gpu::kVisibleBrickSize);

// Voxels of brick `index` (x fastest) of a grid of `dims`: the last bricks are cut by the grid.
std::uint64_t brickVoxels(std::uint32_t index, glm::ivec3 bricks, Dims dims) {
  const glm::ivec3 brick(static_cast<int>(index % bricks.x),
                         static_cast<int>(index / bricks.x % bricks.y),
                         static_cast<int>(index / (bricks.x * bricks.y)));
  const glm::ivec3 first = brick * kBrick;
  const glm::ivec3 size = glm::min(first + kBrick, glm::ivec3(dims)) - first;
  return static_cast<std::uint64_t>(size.x) * size.y * size.z;
}

constexpr VkPipelineStageFlags2 kVolumeReaders =
    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;

}  // namespace

int coarseLicStride(double fullLicMs, double budgetMs) {
  int stride = 1;
  while (stride < 8 && fullLicMs / (stride * stride * stride) > budgetMs) stride *= 2;
  return stride;
}

int nextCoarseStride(int stride, double coarseMs, double budgetMs) {
  return coarseMs > budgetMs && stride < 8 ? stride * 2 : stride;
}

Result<LicVolumeJob> LicVolumeJob::create(const Context& context, bool doubleBuffered,
                                          bool naiveKernel, std::optional<LicSpecialization> launch,
                                          bool visibleWork, double fullPassShare) {
  LicVolumeJob job;
  job.context_ = &context;
  job.doubleBuffered_ = doubleBuffered;
  // The made flags belong to one volume; the brick variant reads the noise from the field.
  job.visibleWork_ = visibleWork && !doubleBuffered && !naiveKernel;
  job.fullPassShare_ = fullPassShare;
  if (job.visibleWork_) {
    LIC3D_TRY_ASSIGN(job.bricks_, VisibleBricksPass::create(context));
  }
  LIC3D_TRY_ASSIGN(job.licPass_, LicPass::create(context, naiveKernel, launch));
  LIC3D_TRY_ASSIGN(job.histogramPass_, LicHistogramPass::create(context));
  LIC3D_TRY_ASSIGN(job.masks_, SparsityMaskStore::create(context));
  if (!supportsFormat(context, kLicVolumeFormat,
                      VK_FORMAT_FEATURE_2_STORAGE_IMAGE_BIT |
                          VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_FILTER_LINEAR_BIT))
    return unsupportedError(context.deviceInfo().name +
                            " cannot use RG16_UNORM as a filtered storage image");
  return job;
}

void LicVolumeJob::dropField(bool newGrid, const std::optional<FieldPiece>& piece) {
  job_.reset();
  finished_.reset();
  shownParams_.reset();
  shownSetup_.reset();
  piece_ = piece;  // a piece's mask is cut from the whole one: the store tells them apart
  if (newGrid) {
    masks_.release();  // the mask and the volumes live on the field's grid
    for (Image& volume : volumes_) volume = Image();
  }
  front_ = 0;
  shownStride_ = 1;
  fieldChanged_ = false;
}

Result<void> LicVolumeJob::ensureVolume(int index, Dims dims) {
  const VkExtent3D extent = extentOf(dims);
  Image& volume = volumes_[index];
  if (volume && volume.extent().width == extent.width && volume.extent().height == extent.height &&
      volume.extent().depth == extent.depth)
    return {};
  // A coarse volume of another stride: frames still in flight may read the old one.
  if (volume) vkQueueWaitIdle(context_->queue());
  volume = Image();
  ImageDesc desc;
  desc.format = kLicVolumeFormat;
  desc.extent = extent;
  desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
               VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  static constexpr const char* kNames[] = {"lic volume A", "lic volume B", "coarse lic volume A",
                                           "coarse lic volume B"};
  desc.name = kNames[index];
  LIC3D_TRY_ASSIGN(volume, Image::create(*context_, desc));
  return {};
}

int LicVolumeJob::backIndex(int stride) const {
  // Coarse volumes are small: always two, so a drag never shows a half-written one.
  if (stride > 1) return front_ == 2 ? 3 : 2;
  if (!doubleBuffered_) return 0;
  return front_ == 0 ? 1 : 0;
}

Result<void> LicVolumeJob::setVolume(const ScalarVolume& volume, const LicParams& params,
                                     const FieldTextures& textures) {
  const FieldTexture& field = textures.field();
  if (!field.image || volume.dims != field.dims)
    return inputError("the LIC volume's grid does not match the field's");
  job_.reset();
  if (front_ >= 2) front_ = 0;  // a full volume replaces a coarse one
  LIC3D_TRY(ensureVolume(front_, field.dims));
  vkQueueWaitIdle(context_->queue());  // frames may still read the shown volume
  {
    const StageTimer timer("LIC volume upload");
    // RG16: the value, and whether the voxel is drawn; converted on all threads straight into
    // the staging buffer.
    LIC3D_TRY(uploadImageFilled(
        *context_, shownVolume(), volume.values.size() * 2 * sizeof(std::uint16_t),
        [&](void* staging) {
          auto* texels = static_cast<std::uint16_t*>(staging);
          parallelChunks(volume.values.size(), [&](std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) {
              texels[2 * i] = static_cast<std::uint16_t>(
                  std::lround(std::clamp(volume.values[i], 0.0f, 1.0f) * 65535.0f));
              texels[2 * i + 1] = volume.drawn.empty() || volume.drawn[i] ? 65535 : 0;
            }
          });
        }));
  }
  LIC3D_TRY(submitAndWait(
      *context_,
      [&](VkCommandBuffer cmd) {
        histogramPass_.record(cmd, shownVolume(), field, textures.emptySpeed(), 0);
      },
      "lic histogram"));
  // The whole volume is made: a view change makes no brick.
  if (visibleWork_) {
    LIC3D_TRY(bricks_.reserve(field.dims));
    LIC3D_TRY(submitAndWait(
        *context_, [&](VkCommandBuffer cmd) { bricks_.recordAllMade(cmd); }, "bricks made"));
  }
  shownSetup_.reset();
  // No job finished here: the statistics are this volume's histogram, taken directly.
  finished_.reset();
  statistics_ = intensityStatistics(histogramPass_.counts(0));
  shownParams_ = params;
  shownStride_ = 1;
  return {};
}

const Buffer* LicVolumeJob::maskFor(const LicParams& params) const {
  return params.sparsity.distribution == SparsityDistribution::None ? nullptr : &masks_.buffer();
}

std::optional<double> LicVolumeJob::hiddenFraction(Dims dims) const {
  if (!shownParams_ || shownParams_->sparsity.distribution == SparsityDistribution::None)
    return std::nullopt;
  return static_cast<double>(statistics_.maskedVoxels) /
         static_cast<double>(std::max<std::size_t>(voxelCount(shownDims(dims)), 1));
}

std::uint64_t LicVolumeJob::bytes() const {
  std::uint64_t bytes = 0;
  for (const Image& v : volumes_) bytes += v ? v.memorySize() : 0;
  return bytes + masks_.bytes();
}

LicStatus LicVolumeJob::status(Dims dims) const {
  LicStatus status;
  if (!job_) {
    status.pending = finished_.has_value();
    return status;
  }
  status.pending = true;
  status.stride = job_->stride;
  const int slices = coarseDims(dims, job_->stride).z;
  status.fraction = slices > 0 ? static_cast<double>(job_->nextZ) / slices : 0.0;
  status.waitingForMask = job_->needsMask;
  return status;
}

// ---- Jobs --------------------------------------------------------------------------------------

Result<void> LicVolumeJob::start(const LicParams& params, const FieldTextures& textures, bool force,
                                 int stride) {
  LIC3D_TRY(validate(params));
  if (stride != 1 && stride != 2 && stride != 4 && stride != 8)
    return inputError("the LIC stride must be 1, 2, 4 or 8, got " + std::to_string(stride));
  const Dims dims = textures.field().dims;
  if (!textures.field().image) return inputError("no vector field and noise were set");
  const SparsityParams sparsity = maskParams(params);
  LIC3D_TRY(validate(sparsity, piece_ ? piece_->wholeDims : dims));
  if (!force && job_ && job_->params == params && job_->stride == stride) return {};
  fieldChanged_ = false;  // the job reads the field texture as it is now
  Job job;
  job.params = params;
  job.stride = stride;
  job.needsMask =
      sparsity.distribution != SparsityDistribution::None && !masks_.holds(sparsity, dims, piece_);
  // A mask the dropped job was waiting for serves this one (a new field, e.g. the next time of a
  // series, does not change it): the store neither makes it again nor waits for it here.
  if (job.needsMask) masks_.request(sparsity, dims, piece_);
  job_ = std::move(job);
  return {};
}

Result<void> LicVolumeJob::request(const LicParams& params, const FieldTextures& textures,
                                   int stride) {
  const std::optional<LicParams>& latest = finished_ ? finished_->params : shownParams_;
  const int latestStride = finished_ ? finished_->stride : shownStride_;
  if (!job_ && latest && *latest == params && latestStride == stride && !fieldChanged_) return {};
  return start(params, textures, fieldChanged_, stride);
}

// Whether the job's mask is on the GPU; puts it there when it is ready (`wait`: waits for it).
Result<bool> LicVolumeJob::prepareMask(bool wait) {
  if (!job_->needsMask) return true;
  const Result<bool> ready = masks_.prepare(wait);
  if (!ready) {
    Error error = ready.error();
    job_.reset();
    return error;
  }
  if (*ready) job_->needsMask = false;
  return *ready;
}

Result<void> LicVolumeJob::waitForMask(const FieldTextures&) {
  if (!job_) return {};
  LIC3D_TRY_ASSIGN([[maybe_unused]] const bool ready, prepareMask(true));
  return {};
}

Result<LicWork> LicVolumeJob::record(VkCommandBuffer cmd, const FieldTextures& textures,
                                     int maxSlices, std::uint32_t slot) {
  LicWork work;
  // A finished volume waits for collectStatistics; the next job would overwrite it.
  if (!job_ || finished_) return work;
  const FieldTexture& field = textures.field();
  const Dims dims = field.dims;
  LIC3D_TRY_ASSIGN(const bool maskReady, prepareMask(false));
  if (!maskReady) {
    work.waitingForMask = true;
    return work;
  }
  const int stride = job_->stride;
  const Dims grid = coarseDims(dims, stride);
  const int index = backIndex(stride);
  LIC3D_TRY(ensureVolume(index, grid));
  Image& back = volumes_[index];
  work.stride = stride;
  if (!job_->nothingListed) {
    const int zBegin = job_->nextZ;
    work.began = zBegin == 0;
    // Whole workgroups (whole brick layers): a slab thinner than a workgroup is deep would leave
    // invocations idle.
    const int depth = job_->overBricks ? kBrick : licPass_.launchDepth();
    const int slices = (std::max(1, maxSlices) + depth - 1) / depth * depth;
    const int zEnd = std::min(grid.z, zBegin + slices);
    if (zBegin == 0 && job_->forget) {
      // The old contents are discarded; earlier frames and histograms must be done reading.
      if (index == front_) shownParams_.reset();
      imageBarrier(cmd, back.handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                   kVolumeReaders | VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE,
                   VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    } else if (zBegin == 0) {
      // Bricks that became visible join those made before, which stay.
      imageBarrier(cmd, back.handle(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                   VK_IMAGE_LAYOUT_GENERAL, kVolumeReaders | VK_PIPELINE_STAGE_2_COPY_BIT,
                   VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                   VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    } else {
      memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    }
    LIC3D_TRY(recordSlab(cmd, textures, back, zBegin, zEnd));
    work.slicesRecorded = zEnd - zBegin;
    job_->nextZ = zEnd;
    if (zEnd < grid.z) return work;
    // The full pass made every brick (of the full volume: a coarse one marks none).
    if (visibleWork_ && !job_->overBricks && stride == 1 && bricks_.bricks() == brickCounts(dims))
      bricks_.recordAllMade(cmd);

    imageBarrier(cmd, back.handle(), VK_IMAGE_LAYOUT_GENERAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                 VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                 kVolumeReaders | VK_PIPELINE_STAGE_2_COPY_BIT,
                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
  }
  histogramPass_.record(cmd, back, field, textures.emptySpeed(), slot,
                        job_->visible ? &bricks_.visible() : nullptr, stride);
  // Shown once its statistics are read back: a frame never draws a volume with another's
  // contrast stretch. A coarse volume's histogram samples the full one's voxels evenly, so its
  // contrast stretch is close to the full volume's.
  finished_ = Finished{job_->params, slot, job_->visible, index, stride};
  job_.reset();
  ++licDispatches_;
  work.finished = true;
  return work;
}

void LicVolumeJob::collectStatistics(std::uint32_t slot) {
  if (!finished_ || finished_->slot != slot) return;
  statistics_ = intensityStatistics(histogramPass_.counts(slot));
  front_ = finished_->volume;
  shownParams_ = finished_->params;
  shownSetup_ = finished_->visible;
  shownStride_ = finished_->stride;
  finished_.reset();
}

Result<void> LicVolumeJob::recordSlab(VkCommandBuffer cmd, const FieldTextures& textures,
                                      Image& back, int zBegin, int zEnd) {
  const FieldTexture& field = textures.field();
  if (!job_->overBricks)
    return licPass_.record(cmd, field, maskFor(job_->params), masks_.beyond(), back, job_->params,
                           zBegin, zEnd, textures.separateNoise(), job_->stride);
  return licPass_.recordBricks(cmd, field, maskFor(job_->params), masks_.beyond(), back,
                               job_->params, bricks_, zBegin / kBrick,
                               (zEnd + kBrick - 1) / kBrick);
}

Result<void> LicVolumeJob::classify(const FieldTextures& textures) {
  const FieldTexture& field = textures.field();
  const Dims dims = field.dims;
  LIC3D_TRY(bricks_.reserve(dims));
  Result<void> recorded;
  LIC3D_TRY(submitAndWait(
      *context_,
      [&](VkCommandBuffer cmd) {
        if (job_->forget) bricks_.recordForget(cmd);
        recorded = bricks_.record(cmd, field, *job_->visible);
        bricks_.recordReadback(cmd);
      },
      "visible bricks"));
  LIC3D_TRY(std::move(recorded));
  // Whether the listed bricks are so many that the full pass costs less (read back here: the
  // blocking path waits anyway).
  const glm::ivec3 bricks = bricks_.bricks();
  VisibleWorkCounts counts;
  counts.bricks = static_cast<std::uint64_t>(bricks.x) * bricks.y * bricks.z;
  for (const std::uint32_t flag : bricks_.visibleFlags()) counts.visible += flag;
  std::uint64_t listedVoxels = 0;
  for (const std::vector<std::uint32_t>& layer : bricks_.listedBricks()) {
    counts.made += layer.size();
    for (const std::uint32_t index : layer) listedVoxels += brickVoxels(index, bricks, dims);
  }
  job_->classified = true;
  if (job_->forget &&
      static_cast<double>(listedVoxels) >= fullPassShare_ * static_cast<double>(voxelCount(dims))) {
    counts.fullPass = true;
    counts.made = counts.bricks;
    job_->overBricks = false;
  } else {
    job_->overBricks = true;
    // The volume stays as it is; only its statistics are of the new classification.
    job_->nothingListed = counts.made == 0 && !job_->forget;
  }
  visibleCounts_ = counts;
  return {};
}

Result<bool> LicVolumeJob::update(const LicParams& params, const FieldTextures& textures,
                                  const ProgressCallback& progress,
                                  const VisibleBricksSetup* visible, int stride) {
  const bool licChanges =
      !shownParams_ || !(*shownParams_ == params) || shownStride_ != stride || fieldChanged_;
  if (visibleWork(params) && visible && stride == 1) {
    if (!job_ && !licChanges && shownSetup_ && sameClassification(*shownSetup_, *visible))
      return false;
    const bool resume = job_ && job_->params == params && job_->visible &&
                        sameClassification(*job_->visible, *visible) && !fieldChanged_;
    if (!resume) {
      LIC3D_TRY(start(params, textures, true));
      job_->visible = *visible;
      job_->forget = licChanges;
    }
  } else {
    if (!job_ && !licChanges) return false;
    LIC3D_TRY(start(params, textures, fieldChanged_, stride));
  }
  const Dims dims = coarseDims(textures.field().dims, stride);
  if (visibleWork_) LIC3D_TRY(bricks_.reserve(dims));
  const int slab = progress ? (dims.z + kProgressSlabs - 1) / kProgressSlabs : dims.z;
  while (job_) {
    // Stopped before a slab starts (also before the first: a stop asked for during what came
    // before, a brick's upload): the pending job goes on where it stopped when update() is
    // called again.
    if (progress.stopRequested()) return cancelledError();
    LIC3D_TRY(waitForMask(textures));
    if (job_->visible && !job_->classified) {
      const StageTimer timer("visible bricks");
      LIC3D_TRY(classify(textures));
      continue;  // a stop asked for meanwhile is seen before the LIC starts
    }
    Result<LicWork> work = LicWork{};
    const StageTimer timer("LIC");
    LIC3D_TRY(submitAndWait(
        *context_, [&](VkCommandBuffer cmd) { work = record(cmd, textures, slab, 0); },
        "lic compute"));
    LIC3D_TRY(work);
    if (work->finished) collectStatistics(0);
    if (progress && work->slicesRecorded > 0)
      progress(job_ ? static_cast<double>(job_->nextZ) / dims.z : 1.0);
  }
  return true;
}

Result<ScalarVolume> LicVolumeJob::read(const FieldTextures& textures) const {
  if (!shownParams_) return inputError("no LIC volume has been computed");
  const FieldTexture& field = textures.field();
  ScalarVolume volume;
  volume.dims = shownDims(field.dims);
  volume.geometry = field.geometry;
  volume.geometry.spacing *= static_cast<double>(shownStride_);
  resizeLarge(volume.values, voxelCount(volume.dims));
  if (shownParams_->sparsity.distribution != SparsityDistribution::None)
    resizeLarge(volume.drawn, volume.values.size());
  LIC3D_TRY(readInto(Dims(0), volume.dims, memoryTarget(volume), Dims(0)));
  return volume;
}

namespace {

// Texels of the LIC volume (RG16: the value, whether drawn) converted into `count` values (and
// drawn flags where `drawn` is given; hidden voxels NaN where it is not and `sparse`). Returns
// the drawn voxels.
std::uint64_t convertTexels(const std::byte* texels, std::size_t count, bool sparse, float* values,
                            std::uint8_t* drawn) {
  std::uint64_t shown = 0;
  for (std::size_t i = 0; i < count; ++i) {
    std::uint16_t texel[2];
    std::memcpy(texel, texels + 4 * i, 4);
    const bool isDrawn = !sparse || texel[1] >= 32768;
    shown += isDrawn ? 1 : 0;
    if (drawn) {
      drawn[i] = isDrawn ? 1 : 0;
      values[i] = static_cast<float>(texel[0]) / 65535.0f;
    } else {
      values[i] = isDrawn ? static_cast<float>(texel[0]) / 65535.0f
                          : std::numeric_limits<float>::quiet_NaN();
    }
  }
  return shown;
}

}  // namespace

Result<std::uint64_t> LicVolumeJob::readInto(Dims from, Dims extent, const VoxelTarget& target,
                                             Dims at) const {
  if (!shownParams_) return inputError("no LIC volume has been computed");
  const bool sparse = shownParams_->sparsity.distribution != SparsityDistribution::None;
  // The region's rows are adjacent in the target when they span its x and y (a slab): a slab is
  // then one run of the target, else each row is one.
  const bool adjacent = extent.x == target.dims.x && extent.y == target.dims.y;
  const std::size_t row = static_cast<std::size_t>(extent.x);
  std::atomic<std::uint64_t> drawn{0};
  std::mutex mutex;
  std::optional<Error> failure;
  // The time in target.write, summed over the threads, and in the chunks in all.
  std::atomic<std::int64_t> writeNs{0}, chunkNs{0};
  double writeSeconds = 0.0;  // the share of the slabs' wall time spent writing
  const auto slab = [&](const void* texels, int firstLayer, int layers) -> Result<void> {
    const std::size_t count = row * static_cast<std::size_t>(extent.y) * layers;
    const Clock::time_point slabStart = Clock::now();
    writeNs = 0;
    chunkNs = 0;
    parallelChunks(
        count,
        [&](std::size_t begin, std::size_t end) {
          thread_local std::vector<float> local;
          const Clock::time_point chunkStart = Clock::now();
          std::uint64_t shown = 0;
          for (std::size_t i = begin; i < end;) {
            // The run from slab voxel i: to the chunk's end, or its row's.
            const std::size_t rowIndex = i / row;
            const std::size_t n = adjacent ? end - i : std::min(end, (rowIndex + 1) * row) - i;
            const int y = static_cast<int>(rowIndex % static_cast<std::size_t>(extent.y));
            const int z = static_cast<int>(rowIndex / static_cast<std::size_t>(extent.y));
            const std::uint64_t first =
                voxelIndex(target.dims, at.x + static_cast<int>(i - rowIndex * row), at.y + y,
                           at.z + firstLayer + z);
            const std::byte* in = static_cast<const std::byte*>(texels) + 4 * i;
            if (target.values) {
              shown += convertTexels(in, n, sparse, target.values + first,
                                     target.drawn ? target.drawn + first : nullptr);
            } else {
              local.resize(n);
              shown += convertTexels(in, n, sparse, local.data(), nullptr);
              const Clock::time_point writing = Clock::now();
              Result<void> written = target.write(first, local.data(), n);
              writeNs +=
                  std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - writing)
                      .count();
              if (!written) {
                const std::lock_guard lock(mutex);
                if (!failure) failure = written.error();
                return;
              }
            }
            i += n;
          }
          drawn += shown;
          chunkNs += std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - chunkStart)
                         .count();
        },
        std::size_t{1} << 18);
    if (chunkNs > 0)
      writeSeconds += secondsSince(slabStart) * static_cast<double>(writeNs.load()) /
                      static_cast<double>(chunkNs.load());
    if (failure) return *failure;
    return {};
  };
  const Clock::time_point start = Clock::now();
  const Result<void> read = readback_.read(
      *context_, shownVolume(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 4, from, extent, slab);
  // The slabs' wall time in the writes is the write stage's where the target names one.
  const bool ownStage = target.writeStage != nullptr;
  addStageTime("volume read-back", secondsSince(start) - (ownStage ? writeSeconds : 0.0));
  addStageBytes("volume read-back", voxelCount(extent) * 4);
  if (ownStage) {
    addStageTime(target.writeStage, writeSeconds);
    addStageBytes(target.writeStage, voxelCount(extent) * sizeof(float));
  }
  LIC3D_TRY(read);
  return drawn.load();
}

Result<double> timeLicDispatch(const Context& context, LicVolumeJob& job,
                               const FieldTextures& textures, const GpuTimer& timer,
                               const LicParams& params) {
  if (!timer.valid()) return unsupportedError("the device has no timestamp queries");
  LIC3D_TRY(job.start(params, textures, true));
  LIC3D_TRY(job.waitForMask(textures));
  Result<LicWork> work = LicWork{};
  LIC3D_TRY(submitAndWait(
      context,
      [&](VkCommandBuffer cmd) {
        timer.reset(cmd, 0);
        timer.begin(cmd, 0);
        work = job.record(cmd, textures, textures.field().dims.z, 0);
        timer.end(cmd, 0);
      },
      "lic timing"));
  LIC3D_TRY(work);
  job.collectStatistics(0);
  return timer.milliseconds(0);
}

}  // namespace lic3d
