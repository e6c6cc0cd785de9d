// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The sparsity mask the LIC volume job reads, bit-packed in a storage buffer
// (shaders/sparsity_mask.h). The checkerboard, Halton and Hammersley masks of a whole grid are made
// on the GPU (SparsityMaskPass) when asked for; the others (Poisson disk, best candidate,
// jittering) and the masks of pieces are made on a worker thread and uploaded, and kept packed in a
// cache of recent masks, so a change back to one seen before is an upload (docs/LIC_SEMANTICS.md,
// "Where masks are made").

#include <cstddef>
#include <cstdint>
#include <future>
#include <list>
#include <memory>
#include <optional>
#include <vector>

#include "core/error.h"
#include "core/lic_params.h"
#include "core/volume.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"
#include "lic/sparsity.h"
#include "passes/sparsity_mask_pass.h"

namespace lic3d {

// Host memory the cache of CPU-made masks may hold (an eighth of a byte per voxel: 32 masks of
// 256^3). The least recently used go first.
inline constexpr std::size_t kSparsityMaskCacheBytes = std::size_t{64} << 20;

class SparsityMaskStore {
 public:
  // `context` must outlive the store.
  static Result<SparsityMaskStore> create(const Context& context);

  // Whether the buffer holds the mask of `params` on grid `dims` (of `piece`, if set).
  bool holds(const SparsityParams& params, Dims dims, const std::optional<FieldPiece>& piece) const;
  // Asks for that mask (validated by the caller): a CPU-made one not in the cache starts on a
  // worker thread now. Nothing happens if it is held or already asked for.
  void request(const SparsityParams& params, Dims dims, const std::optional<FieldPiece>& piece);
  // Whether the mask asked for is in the buffer: made on the GPU, or uploaded once the worker
  // finished it (`wait`: waits for the worker). Waits for the queue to be idle before the buffer
  // changes, since frames in flight may still read the old mask. A failure forgets the request.
  Result<bool> prepare(bool wait);
  // Frees the buffer (the grid changed).
  void release();

  const Buffer& buffer() const { return bits_; }
  const MaskBeyondGrid& beyond() const { return beyond_; }
  // Masks put in the buffer so far (made on the GPU, uploaded, or taken from the cache), and those
  // of them taken from the cache.
  std::uint64_t builds() const { return builds_; }
  std::uint64_t cacheHits() const { return cacheHits_; }
  // Device memory of the buffer.
  std::uint64_t bytes() const { return bits_.size(); }

 private:
  struct Key {
    SparsityParams params;
    Dims dims{0};
    std::optional<FieldPiece> piece;
    bool operator==(const Key&) const = default;
  };
  struct Packed {
    std::vector<std::uint32_t> words;
    MaskBeyondGrid beyond;
    std::size_t blackCount = 0;
  };
  using PackedResult = Result<std::shared_ptr<const Packed>>;

  Result<void> reserve(Dims dims);
  Result<void> makeOnGpu(const Key& key);
  void remember(const Key& key, std::shared_ptr<const Packed> packed);

  const Context* context_ = nullptr;
  SparsityMaskPass pass_;
  Buffer bits_;
  Buffer count_;     // the GPU's black voxel count
  Buffer readback_;  // its copy for the host
  std::optional<Key> held_;
  std::optional<Key> asked_;
  std::shared_future<PackedResult> worker_;  // valid while a CPU-made mask is asked for
  std::list<std::pair<Key, std::shared_ptr<const Packed>>> cache_;  // most recent first
  std::size_t cacheBytes_ = 0;
  MaskBeyondGrid beyond_;
  std::uint64_t builds_ = 0;
  std::uint64_t cacheHits_ = 0;
};

}  // namespace lic3d
