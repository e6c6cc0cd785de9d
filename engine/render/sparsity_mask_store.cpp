// SPDX-License-Identifier: BSD-3-Clause
#include "render/sparsity_mask_store.h"

#include <chrono>
#include <utility>

#include "core/stage_times.h"
#include "gpu/submit.h"

namespace lic3d {

Result<SparsityMaskStore> SparsityMaskStore::create(const Context& context) {
  SparsityMaskStore store;
  store.context_ = &context;
  LIC3D_TRY_ASSIGN(store.pass_, SparsityMaskPass::create(context));
  constexpr VkBufferUsageFlags kUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  LIC3D_TRY_ASSIGN(store.count_, Buffer::create(context, sizeof(std::uint32_t), kUsage,
                                                MemoryUse::DeviceLocal, "sparsity mask count"));
  LIC3D_TRY_ASSIGN(store.readback_,
                   Buffer::create(context, sizeof(std::uint32_t), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                  MemoryUse::Readback, "sparsity mask count readback"));
  return store;
}

bool SparsityMaskStore::holds(const SparsityParams& params, Dims dims,
                              const std::optional<FieldPiece>& piece) const {
  return held_ && *held_ == Key{params, dims, piece};
}

void SparsityMaskStore::request(const SparsityParams& params, Dims dims,
                                const std::optional<FieldPiece>& piece) {
  const Key key{params, dims, piece};
  if ((held_ && *held_ == key) || (asked_ && *asked_ == key)) return;
  asked_ = key;
  worker_ = {};
  if (!piece && madeOnGpu(params.distribution)) return;  // made by prepare()
  for (auto it = cache_.begin(); it != cache_.end(); ++it)
    if (it->first == key) {
      std::promise<PackedResult> ready;
      ready.set_value(it->second);
      worker_ = ready.get_future().share();
      cache_.splice(cache_.begin(), cache_, it);
      ++cacheHits_;
      return;
    }
  // Some distributions take seconds (best candidate): never on the thread that draws.
  worker_ = std::async(std::launch::async, [key]() -> PackedResult {
              LIC3D_TRY_ASSIGN(const SparsityMask mask,
                               key.piece ? makeSparsityMaskPiece(key.params, *key.piece, key.dims)
                                         : makeSparsityMask(key.params, key.dims));
              auto packed = std::make_shared<Packed>();
              packed->words = packSparsityMask(mask);
              packed->beyond = mask.beyond;
              packed->blackCount = mask.blackCount;
              return std::shared_ptr<const Packed>(std::move(packed));
            }).share();
}

Result<void> SparsityMaskStore::reserve(Dims dims) {
  const VkDeviceSize bytes = sparsityMaskWords(dims) * sizeof(std::uint32_t);
  if (bits_.size() == bytes) return {};
  bits_ = Buffer();
  LIC3D_TRY_ASSIGN(
      bits_, Buffer::create(*context_, bytes,
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                            MemoryUse::DeviceLocal, "sparsity mask"));
  return {};
}

Result<void> SparsityMaskStore::makeOnGpu(const Key& key) {
  Result<void> recorded;
  LIC3D_TRY(submitAndWait(
      *context_,
      [&](VkCommandBuffer cmd) {
        // Fails before recording anything (the pipeline), or not at all.
        recorded = pass_.record(cmd, key.params, key.dims, bits_, count_);
        if (!recorded) return;
        const VkBufferCopy region{0, 0, sizeof(std::uint32_t)};
        vkCmdCopyBuffer(cmd, count_.handle(), readback_.handle(), 1, &region);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
      },
      "sparsity mask"));
  LIC3D_TRY(recorded);
  const auto blackCount = *static_cast<const std::uint32_t*>(readback_.mapped());
  beyond_ = maskBeyondGrid(key.params, blackCount, key.dims);
  return {};
}

void SparsityMaskStore::remember(const Key& key, std::shared_ptr<const Packed> packed) {
  for (const auto& [cached, value] : cache_)
    if (cached == key) return;
  const std::size_t bytes = packed->words.size() * sizeof(std::uint32_t);
  if (bytes > kSparsityMaskCacheBytes) return;
  cache_.emplace_front(key, std::move(packed));
  cacheBytes_ += bytes;
  while (cacheBytes_ > kSparsityMaskCacheBytes) {
    cacheBytes_ -= cache_.back().second->words.size() * sizeof(std::uint32_t);
    cache_.pop_back();
  }
}

Result<bool> SparsityMaskStore::prepare(bool wait) {
  if (!asked_) return held_.has_value();
  const Key key = *asked_;
  const bool onGpu = !worker_.valid();
  if (!onGpu) {
    if (wait) {
      const StageTimer timer("mask");
      worker_.wait();
    }
    if (worker_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return false;
  }
  // Slabs of an earlier job recorded into frames still in flight may read the old mask.
  vkQueueWaitIdle(context_->queue());
  held_.reset();
  asked_.reset();
  if (onGpu) {
    const StageTimer timer("mask on the GPU");
    LIC3D_TRY(reserve(key.dims));
    LIC3D_TRY(makeOnGpu(key));
  } else {
    const PackedResult packed = worker_.get();
    worker_ = {};
    if (!packed) return packed.error();
    const StageTimer timer("mask upload");
    LIC3D_TRY(reserve(key.dims));
    const std::vector<std::uint32_t>& words = (*packed)->words;
    LIC3D_TRY(uploadBuffer(*context_, bits_, words.data(), words.size() * sizeof(std::uint32_t)));
    beyond_ = (*packed)->beyond;
    remember(key, *packed);
  }
  held_ = key;
  ++builds_;
  return true;
}

void SparsityMaskStore::release() {
  held_.reset();
  bits_ = Buffer();
}

}  // namespace lic3d
