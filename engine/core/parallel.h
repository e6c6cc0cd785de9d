// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The one thread fan-out of the CPU work (the reference LIC, the sparsity samplers): tasks
// handed out in order to the threads the process may run on.

#include <cstddef>
#include <functional>

#include "core/progress.h"

namespace lic3d {

// The CPUs this process may run on: its affinity mask (taskset, a batch system's CPU set), else
// the hardware's thread count, at most the limit set by setThreadLimit (`--threads`). At least 1.
unsigned availableThreads();
// Bounds availableThreads() for the whole process (0: no bound).
void setThreadLimit(unsigned threads);

// Calls task(i) for every i in [0, count) on up to `threads` threads (0: availableThreads()), the
// calling thread among them; a thread that finishes a task takes the next one not yet taken.
// After each task the calling thread ran, `progress` (when given) gets the fraction of all tasks
// finished, on the calling thread; once its stop is requested no further task starts. Tasks must
// not write what other tasks read: the result is then the same whichever thread ran which task.
// If tasks throw, the exception of the lowest one is rethrown here once all have finished.
void parallelFor(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& task,
                 const ProgressCallback& progress = {});
// [0, count) in consecutive chunks of at least `grain` items, chunk(begin, end) for each, on
// availableThreads(). For loops over voxels whose iterations write only their own items.
void parallelChunks(std::size_t count, const std::function<void(std::size_t, std::size_t)>& chunk,
                    std::size_t grain = std::size_t{1} << 15);
// memcpy of `bytes` in chunks of at least a MiB on availableThreads() (staging copies of whole
// volumes).
void parallelCopy(void* to, const void* from, std::size_t bytes);

// Asks the kernel to back [data, data + bytes) with huge pages where it can (transparent huge
// pages in `madvise` mode): a volume-sized array then costs one page fault per 2 MiB instead of
// one per 4 KiB when it is first written. A no-op for small ranges and where unsupported.
void adviseHugePages(void* data, std::size_t bytes);

// Writes a zero byte into every page of [data, data + bytes) on availableThreads(), for ranges
// of 64 MiB or more (smaller ones: nothing): the kernel's page faults (and its clearing of each
// page) then run on all threads rather than in the first serial pass over a new array. The
// range must be memory the caller owns and may overwrite.
void touchPagesInParallel(void* data, std::size_t bytes);

// v.resize(count) for volume-sized arrays: the memory is advised to huge pages and its new part's
// pages faulted in on all threads before resize first writes the new items.
template <class Vector>
void resizeLarge(Vector& v, std::size_t count) {
  const std::size_t old = v.size();
  v.reserve(count);
  adviseHugePages(v.data(), v.capacity() * sizeof(*v.data()));
  if (count > old) touchPagesInParallel(v.data() + old, (count - old) * sizeof(*v.data()));
  v.resize(count);
}

}  // namespace lic3d
